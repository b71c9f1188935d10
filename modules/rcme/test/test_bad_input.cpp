// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Every public function on malformed or hopeless input: an exception naming the argument, or a
// non-success status with a fully written zero mask, never a crash or a confident model.

#include "test_precomp.hpp"

#include <algorithm>
#include <cctype>
#include <functional>

namespace opencv_test {
namespace {

// Runs `call` and checks it throws cv::Exception whose message names `argument`.
void expectErrorNaming(const std::function<void()>& call, const std::string& argument)
{
    try {
        call();
        ADD_FAILURE() << "no exception; expected one naming " << argument;
    } catch (const cv::Exception& e) {
        EXPECT_NE(std::string(e.what()).find(argument), std::string::npos)
            << "message '" << e.what() << "' does not name " << argument;
    }
}

// Uniform pixels. cv::RNG streams of nearby seeds are correlated (multiply-with-carry), so the
// seed is spread by a large odd multiplier and each call draws from its own stream.
Mat randomPoints(int n, int seed, double extent = 640)
{
    Mat p(n, 2, CV_64F);
    RNG rng(0x9E3779B97F4A7C15ull * static_cast<uint64>(seed + 1));
    rng.fill(p, RNG::UNIFORM, 0, extent);
    return p;
}

Mat cameraMatrix()
{
    return Mat(Matx33d(500, 0, 320, 0, 500, 240, 0, 0, 1));
}

// Every estimating entry point, called with (points1, points2, K); returns the status and
// checks the mask is Nx1 CV_8U zeros when the status is not success.
struct EntryPoint
{
    const char* name;
    std::function<Status(const Mat&, const Mat&, const Mat&, Mat&)> call;
};

std::vector<EntryPoint> entryPoints(Method method = METHOD_STANDARD)
{
    Params params;
    params.method = method;
    return {
        {"findFundamentalMat",
         [params](const Mat& a, const Mat& b, const Mat&, Mat& mask) {
             Status s;
             findFundamentalMat(a, b, params, mask, s);
             return s;
         }},
        {"findFundamentalMat(K)",
         [params](const Mat& a, const Mat& b, const Mat& K, Mat& mask) {
             Status s;
             findFundamentalMat(a, b, K, params, mask, s);
             return s;
         }},
        {"findEssentialMat",
         [params](const Mat& a, const Mat& b, const Mat& K, Mat& mask) {
             Status s;
             findEssentialMat(a, b, K, params, mask, s);
             return s;
         }},
        {"recoverPose",
         [params](const Mat& a, const Mat& b, const Mat& K, Mat& mask) {
             Status s;
             Mat E, R, t, cov;
             recoverPose(a, b, K, E, R, t, params, mask, s, cov);
             if (s != STATUS_SUCCESS) {
                 EXPECT_TRUE(E.empty() && R.empty() && t.empty() && cov.empty());
             }
             return s;
         }},
        {"estimateRelativeMotion",
         [params](const Mat& a, const Mat& b, const Mat& K, Mat& mask) {
             const Report r = estimateRelativeMotion(a, b, K, params);
             mask = r.mask;
             if (r.status != STATUS_SUCCESS) {
                 EXPECT_TRUE(r.F.empty() && r.R.empty() && r.t.empty());
                 EXPECT_FALSE(r.message.empty());
             }
             return r.status;
         }},
    };
}

TEST(Rcme_BadInput, malformed_points_throw_naming_the_argument)
{
    const Mat good = randomPoints(50, 1), K = cameraMatrix();
    Mat nan = good.clone(), inf = good.clone();
    nan.at<double>(7, 1) = std::numeric_limits<double>::quiet_NaN();
    inf.at<double>(3, 0) = std::numeric_limits<double>::infinity();
    const Mat threeColumns(50, 3, CV_64F, Scalar(1));
    const Mat twoChannelsTwoColumns(50, 2, CV_64FC2, Scalar::all(1));
    const Mat threeChannels(50, 1, CV_64FC3, Scalar::all(1));
    for (const EntryPoint& entry : entryPoints()) {
        SCOPED_TRACE(entry.name);
        Mat mask;
        expectErrorNaming([&] { entry.call(Mat(), good, K, mask); }, "points1");
        expectErrorNaming([&] { entry.call(good, Mat(), K, mask); }, "points2");
        expectErrorNaming([&] { entry.call(nan, good, K, mask); }, "points1");
        expectErrorNaming([&] { entry.call(good, inf, K, mask); }, "points2");
        expectErrorNaming([&] { entry.call(threeColumns, good, K, mask); }, "points1");
        expectErrorNaming([&] { entry.call(good, twoChannelsTwoColumns, K, mask); }, "points2");
        expectErrorNaming([&] { entry.call(threeChannels, good, K, mask); }, "points1");
        expectErrorNaming([&] { entry.call(good, randomPoints(49, 2), K, mask); }, "points1");
    }
}

TEST(Rcme_BadInput, malformed_camera_matrix_throws_naming_it)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2);
    const Mat singular = Mat(Matx33d(0, 0, 320, 0, 0, 240, 0, 0, 1));
    const Mat notProjective = Mat(Matx33d(500, 0, 320, 0, 500, 240, 1, 0, 1));
    const Mat nan = Mat(Matx33d(500, 0, NAN, 0, 500, 240, 0, 0, 1));
    const Mat twoByThree(2, 3, CV_64F, Scalar(1));
    const Mat fourByFour = Mat::eye(4, 4, CV_64F);
    const Mat negativeFocal = Mat(Matx33d(500, 0, 320, 0, -500, 240, 0, 0, 1));
    for (const EntryPoint& entry : entryPoints()) {
        if (std::string(entry.name) == "findFundamentalMat")
            continue; // takes no camera matrix
        SCOPED_TRACE(entry.name);
        Mat mask;
        for (const Mat& K : {singular, notProjective, nan, twoByThree, fourByFour, negativeFocal})
            expectErrorNaming([&] { entry.call(p1, p2, K, mask); }, "cameraMatrix");
    }
    Mat E, R, t, mask;
    Status status;
    expectErrorNaming([&] { findEssentialMat(p1, p2, Mat(), Params(), mask, status); },
                      "cameraMatrix");
    expectErrorNaming([&] { recoverPose(p1, p2, Mat(), E, R, t, Params(), mask, status); },
                      "cameraMatrix");
}

TEST(Rcme_BadInput, bad_params_throw_naming_the_field)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2);
    struct Case
    {
        const char* field;
        std::function<void(Params&)> spoil;
    };
    const std::vector<Case> cases = {
        {"Params.method", [](Params& p) { p.method = static_cast<Method>(3); }},
        {"Params.sampler", [](Params& p) { p.sampler = static_cast<SamplerKind>(9); }},
        {"Params.solver", [](Params& p) { p.solver = static_cast<MinimalSolverKind>(9); }},
        {"Params.verification",
         [](Params& p) { p.verification = static_cast<VerificationKind>(3); }},
        {"Params.scoring", [](Params& p) { p.scoring = static_cast<ScoringKind>(3); }},
        {"Params.sigma", [](Params& p) { p.sigma = 0; }},
        {"Params.sigma", [](Params& p) { p.sigma = NAN; }},
        {"Params.threshold", [](Params& p) { p.threshold = INFINITY; }},
        {"Params.confidence", [](Params& p) { p.confidence = 1.0; }},
        {"Params.cleanSampleSuccessRate", [](Params& p) { p.cleanSampleSuccessRate = -0.1; }},
        {"Params.cleanSampleSuccessRate", [](Params& p) { p.cleanSampleSuccessRate = 1.5; }},
        {"Params.maxIterations", [](Params& p) { p.maxIterations = 0; }},
        {"Params.maxIterations", [](Params& p) { p.maxIterations = 2000000000; }},
        {"Params.refineIterations", [](Params& p) { p.refineIterations = -1; }},
        {"Params.alpha", [](Params& p) { p.alpha = 0; }},
        {"Params.entropyThreshold", [](Params& p) { p.entropyThreshold = NAN; }},
        {"Params.inlierRatioFactor", [](Params& p) { p.inlierRatioFactor = 1.5; }},
        {"Params.priorInlierRatio", [](Params& p) { p.priorInlierRatio = 2; }},
        {"Params.consistencyDof", [](Params& p) { p.consistencyDof = 0; }},
        {"Params.matchQuality",
         [](Params& p) {
             p.sampler = SAMPLER_PROSAC;
             p.matchQuality = Mat(10, 1, CV_64F, Scalar(1)); // 50 points
         }},
        {"Params.matchQuality",
         [](Params& p) {
             p.sampler = SAMPLER_PROSAC;
             p.matchQuality = Mat(50, 1, CV_64F, Scalar(NAN));
         }},
        {"Params.sampleFitIterations", [](Params& p) { p.sampleFitIterations = -1; }},
        {"Params.earlyTerminationEntropy", [](Params& p) { p.earlyTerminationEntropy = NAN; }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.field);
        Params params;
        c.spoil(params);
        Mat mask;
        Status status;
        expectErrorNaming([&] { findFundamentalMat(p1, p2, params, mask, status); }, c.field);
    }
}

TEST(Rcme_BadInput, five_point_solver_needs_a_camera_matrix)
{
    Params params;
    params.solver = SOLVER_FIVE_POINT;
    Mat mask;
    Status status;
    expectErrorNaming(
        [&] { findFundamentalMat(randomPoints(50, 1), randomPoints(50, 2), params, mask, status); },
        "Params.solver");
}

TEST(Rcme_BadInput, too_few_points_is_a_status)
{
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
        for (const EntryPoint& entry : entryPoints(method)) {
            SCOPED_TRACE(entry.name);
            // four: fewer than the 5-point solver's sample (the default with K)
            Mat mask;
            const Status status =
                entry.call(randomPoints(4, 1), randomPoints(4, 2), cameraMatrix(), mask);
            EXPECT_EQ(status, STATUS_NOT_ENOUGH_POINTS);
            ASSERT_EQ(mask.size(), Size(1, 4));
            EXPECT_EQ(mask.type(), CV_8U);
            EXPECT_EQ(countNonZero(mask), 0);
        }
}

TEST(Rcme_BadInput, identical_points_are_degenerate)
{
    const Mat same(60, 2, CV_64F, Scalar(100));
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
        for (const EntryPoint& entry : entryPoints(method)) {
            SCOPED_TRACE(entry.name);
            Mat mask;
            const Status status = entry.call(same, same, cameraMatrix(), mask);
            EXPECT_EQ(status, STATUS_DEGENERATE_CONFIGURATION);
            ASSERT_EQ(mask.size(), Size(1, 60));
            EXPECT_EQ(countNonZero(mask), 0);
        }
}

TEST(Rcme_BadInput, collinear_points_are_degenerate)
{
    Mat p1(60, 2, CV_64F), p2(60, 2, CV_64F);
    for (int i = 0; i < 60; ++i) {
        p1.at<double>(i, 0) = 10 + 7 * i;
        p1.at<double>(i, 1) = 20 + 3 * i;
        p2.at<double>(i, 0) = 15 + 6 * i;
        p2.at<double>(i, 1) = 40 + 2 * i;
    }
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
        for (const EntryPoint& entry : entryPoints(method)) {
            SCOPED_TRACE(entry.name);
            Mat mask;
            EXPECT_NE(entry.call(p1, p2, cameraMatrix(), mask), STATUS_SUCCESS);
            EXPECT_EQ(mask.rows, 60);
        }
}

TEST(Rcme_BadInput, all_outliers_give_poor_quality_input)
{
    // Independent random points: no epipolar geometry explains them better than chance.
    for (int seed = 0; seed < testRuns(5, 1); ++seed) {
        for (Method method :
             {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
            for (const EntryPoint& entry : entryPoints(method)) {
                SCOPED_TRACE(entry.name);
                Mat mask;
                const Status status =
                    entry.call(randomPoints(300, 2 * seed), randomPoints(300, 2 * seed + 1),
                               cameraMatrix(), mask);
                EXPECT_EQ(status, STATUS_POOR_QUALITY_INPUT) << "seed " << seed;
                ASSERT_EQ(mask.size(), Size(1, 300));
                EXPECT_EQ(countNonZero(mask), 0);
            }
    }
}

TEST(Rcme_BadInput, drop_in_overloads_reject_unknown_flags)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2), K = cameraMatrix();
    Mat mask;
    expectErrorNaming([&] { cv::rcme::findFundamentalMat(p1, p2, 99, 3, 0.99, 100, mask); },
                      "method");
    expectErrorNaming([&] { cv::rcme::findEssentialMat(p1, p2, K, 1029, 0.99, 1, 100, mask); },
                      "method");
    expectErrorNaming([&] { cv::rcme::findEssentialMat(p1, p2, -1.0, Point2d(), RANSAC); },
                      "focal");
    // Drop-ins return an empty matrix on failure, as OpenCV does, and still write the mask.
    const Mat F = cv::rcme::findFundamentalMat(p1, p2, FM_RANSAC, 1.0, 0.99, 200, mask);
    EXPECT_TRUE(F.empty());
    EXPECT_EQ(mask.size(), Size(1, 50));
}

TEST(Rcme_BadInput, points_and_camera_matrix_of_any_depth_are_read)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2), K = cameraMatrix();
    Mat K32s;
    K.convertTo(K32s, CV_32S);
    Params params;
    for (int depth : {CV_8U, CV_8S, CV_16U, CV_16S, CV_32S, CV_16F, CV_32F}) {
        SCOPED_TRACE(depth);
        Mat a, b, mask;
        p1.convertTo(a, depth); // saturating: the values do not matter here, the reading does
        p2.convertTo(b, depth);
        Status status;
        EXPECT_NO_THROW(cv::rcme::findEssentialMat(a, b, K32s, params, mask, status));
        EXPECT_EQ(mask.size(), Size(1, 50));
    }
}

TEST(Rcme_BadInput, negative_focal_length_is_rejected_with_a_message)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2);
    Mat K = cameraMatrix();
    K.at<double>(0, 0) = -K.at<double>(0, 0);
    Status status;
    Mat mask;
    try {
        cv::rcme::findEssentialMat(p1, p2, K, Params(), mask, status);
        ADD_FAILURE() << "no exception";
    } catch (const cv::Exception& e) {
        EXPECT_NE(e.err.find("cameraMatrix has a negative focal length"), std::string::npos)
            << e.err;
    }
}

TEST(Rcme_BadInput, recover_pose_from_e_checks_its_arguments)
{
    const Mat p1 = randomPoints(50, 1), p2 = randomPoints(50, 2), K = cameraMatrix();
    const Mat E = Mat(Matx33d(0, -1, 0, 1, 0, 0, 0, 0, 0));
    Mat R, t;
    const Mat nanE = Mat(Matx33d(0, -1, 0, 1, 0, 0, 0, 0, NAN));
    expectErrorNaming([&] { cv::rcme::recoverPose(nanE, p1, p2, K, R, t); }, "E");
    expectErrorNaming([&] { cv::rcme::recoverPose(Mat::eye(2, 3, CV_64F), p1, p2, K, R, t); }, "E");
    expectErrorNaming([&] { cv::rcme::recoverPose(E, p1, p2, Mat(), R, t); }, "cameraMatrix");
    expectErrorNaming([&] { cv::rcme::recoverPose(E, p1, randomPoints(10, 3), K, R, t); },
                      "points1");
    Mat wrongMask(10, 1, CV_8U, Scalar(1));
    expectErrorNaming([&] { cv::rcme::recoverPose(E, p1, p2, K, R, t, wrongMask); }, "mask");
    expectErrorNaming([&] { cv::rcme::recoverPose(E, p1, p2, R, t, 0.0, Point2d()); }, "focal");
}

// 10^7 exact iterations would take minutes; the budget stops every method early with the best
// model so far and its status: success on a clean scene, poor quality input (saying why) on
// random points.
TEST(Rcme_BadInput, time_budget_stops_every_method_with_the_best_so_far)
{
    const SyntheticScene clean = genericTestScene(11, 0.8, 200);
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC}) {
        SCOPED_TRACE(static_cast<int>(method));
        Params params;
        params.method = method;
        params.maxIterations = 10000000;
        params.exactIterations = true;
        params.timeBudget = 0.05;
        const Report good =
            estimateRelativeMotion(clean.points1, clean.points2, clean.cameraMatrix, params);
        EXPECT_LT(good.iterations, params.maxIterations);
        EXPECT_GT(good.iterations, 0);
        EXPECT_EQ(good.status, STATUS_SUCCESS) << good.message;
        EXPECT_LT(compareMotion(good.R, good.t, clean.R, clean.t).rotationDeg, 1.0);

        const Report bad = estimateRelativeMotion(randomPoints(200, 3), randomPoints(200, 4),
                                                  cameraMatrix(), params);
        EXPECT_LT(bad.iterations, params.maxIterations);
        EXPECT_EQ(bad.status, STATUS_POOR_QUALITY_INPUT);
        EXPECT_NE(bad.message.find("timeBudget"), std::string::npos) << bad.message;
    }
    Params nan;
    nan.timeBudget = std::numeric_limits<double>::quiet_NaN();
    expectErrorNaming([&] { estimateRelativeMotion(clean.points1, clean.points2, Mat(), nan); },
                      "timeBudget");
}

TEST(Rcme_BadInput, status_names)
{
    EXPECT_EQ(statusToString(STATUS_SUCCESS), "success");
    EXPECT_EQ(statusToString(STATUS_POOR_QUALITY_INPUT), "poor quality input");
    EXPECT_EQ(statusToString(STATUS_NOT_ENOUGH_POINTS), "not enough points");
    EXPECT_EQ(statusToString(STATUS_DEGENERATE_CONFIGURATION), "degenerate configuration");
    EXPECT_NE(statusToString(static_cast<Status>(42)).find("42"), std::string::npos);
}

TEST(Rcme_BadInput, method_names)
{
    for (Method method :
         {METHOD_RCME, METHOD_PRCME, METHOD_STANDARD, METHOD_MLESAC, METHOD_COV_RANSAC}) {
        const String name = methodName(method);
        EXPECT_EQ(methodFromString(name), method) << name;
        String upper = name;
        std::transform(upper.begin(), upper.end(), upper.begin(),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
        EXPECT_EQ(methodFromString(upper), method) << upper;
    }
    EXPECT_EQ(methodName(METHOD_STANDARD), "standard");
    EXPECT_EQ(methodFromString("cov-ransac"), METHOD_COV_RANSAC);
    EXPECT_EQ(methodFromString("cov_ransac"), METHOD_COV_RANSAC);
    expectErrorNaming([] { methodFromString("ransac"); }, "name");
    expectErrorNaming([] { methodFromString(""); }, "name");
    expectErrorNaming([] { methodName(static_cast<Method>(7)); }, "method");
}

} // namespace
} // namespace opencv_test
