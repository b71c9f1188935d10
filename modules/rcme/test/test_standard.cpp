// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The Standard estimator through the public API: accuracy, conventions, determinism, threads.

#include "test_precomp.hpp"

#include "opencv2/rcme/opencv_geometry.hpp"

#include <algorithm>
#include <optional>
#include <thread>

namespace opencv_test {
namespace {

Params standardParams(int seed = 0)
{
    Params params;
    params.method = METHOD_STANDARD;
    params.randomGeneratorState = seed;
    return params;
}

double median(std::vector<double> v)
{
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

TEST(Rcme_Standard, recovers_pose_on_well_conditioned_scenes)
{
    // Issue 2's acceptance figure: median rotation error < 0.5 deg over >= 100 seeds (w = 0.5,
    // sigma = 1 px, default Params). A failure status counts as a 180 deg error: RANSAC with the
    // 8-point solver draws only ~4 clean samples in 1000 iterations at w = 0.5, and reporting
    // failure then is the intended behaviour, but it must stay rare.
    std::vector<double> rotationErrors, translationErrors;
    int failures = 0;
    const int runs = testRuns(100, 20);
    for (int seed = 0; seed < runs; ++seed) {
        const SyntheticScene scene = genericTestScene(seed);
        Mat E, R, t, mask;
        Status status;
        recoverPose(scene.points1, scene.points2, scene.cameraMatrix, E, R, t, standardParams(seed),
                    mask, status);
        if (status != STATUS_SUCCESS) {
            ++failures;
            rotationErrors.push_back(180);
            translationErrors.push_back(180);
            continue;
        }
        const MotionError error = compareMotion(R, t, scene.R, scene.t);
        rotationErrors.push_back(error.rotationDeg);
        translationErrors.push_back(error.translationDeg);
    }
    if (!kChecksStatistics)
        return;
    EXPECT_LT(median(rotationErrors), 0.5);
    EXPECT_LT(median(translationErrors), 5.0);
    EXPECT_LE(failures, 5);
}

/* A field's automatic value picks one value with K and another without: on `scene`, with and
without K, the default with the field left automatic makes the same run as naming that value, and
a different one (its estimate, or its iteration count) from naming `otherWithK` / `otherWithoutK`.
`set(params, value)` sets the field. */
template <class T, class Set>
void expectAutomaticPicks(const SyntheticScene& scene, Set set, T withK, T withoutK, T otherWithK,
                          T otherWithoutK)
{
    for (bool calibrated : {true, false}) {
        SCOPED_TRACE(calibrated ? "with K" : "without K");
        const auto estimate = [&](std::optional<T> value) {
            Params p;
            if (value)
                set(p, *value);
            return estimateRelativeMotion(scene.points1, scene.points2,
                                          calibrated ? scene.cameraMatrix : Mat(), p);
        };
        const Report automatic = estimate(std::nullopt);
        const Report same = estimate(calibrated ? withK : withoutK);
        const Report other = estimate(calibrated ? otherWithK : otherWithoutK);
        ASSERT_EQ(automatic.status, STATUS_SUCCESS) << automatic.message;
        EXPECT_EQ(automatic.iterations, same.iterations);
        EXPECT_EQ(cv::norm(automatic.F, same.F, NORM_INF), 0.0);
        EXPECT_EQ(countNonZero(automatic.mask != same.mask), 0);
        EXPECT_TRUE(automatic.iterations != other.iterations ||
                    cv::norm(automatic.F, other.F, NORM_INF) > 0);
    }
}

// SOLVER_AUTO is the 5-point solver with K and the 7-point one without.
TEST(Rcme_Standard, auto_solver_is_five_point_with_k_and_seven_point_without)
{
    ASSERT_EQ(Params().solver, SOLVER_AUTO);
    expectAutomaticPicks(
        genericTestScene(3), [](Params& p, MinimalSolverKind solver) { p.solver = solver; },
        SOLVER_FIVE_POINT, SOLVER_SEVEN_POINT, SOLVER_EIGHT_POINT, SOLVER_EIGHT_POINT);
}

// SCORING_AUTO ranks by the inlier count with K and by the truncated cost without.
TEST(Rcme_Standard, auto_scoring_is_the_count_with_k_and_the_truncated_cost_without)
{
    ASSERT_EQ(Params().scoring, SCORING_AUTO);
    expectAutomaticPicks(
        testScene(SCENE_GENERIC, 5, 0.4, 1.0, 200),
        [](Params& p, ScoringKind scoring) { p.scoring = scoring; }, SCORING_INLIER_COUNT,
        SCORING_TRUNCATED_COST, SCORING_TRUNCATED_COST, SCORING_INLIER_COUNT);
    EXPECT_EQ(Params::asPublished(METHOD_STANDARD).scoring, SCORING_INLIER_COUNT);
    EXPECT_EQ(Params::asPublished(METHOD_RCME).scoring, SCORING_AUTO);
}

// cleanSampleSuccessRate 0 (the default) is 0.3 with K and the classic bound's 1 without.
TEST(Rcme_Standard, default_clean_sample_success_rate_is_0_3_with_k_and_1_without)
{
    ASSERT_EQ(Params().cleanSampleSuccessRate, 0.0);
    expectAutomaticPicks(
        testScene(SCENE_GENERIC, 5, 0.6, 1.0, 200),
        [](Params& p, double rate) { p.cleanSampleSuccessRate = rate; }, 0.3, 1.0, 1.0, 0.3);
}

TEST(Rcme_Standard, as_published_is_the_paper_configuration)
{
    const Params p = Params::asPublished(METHOD_RCME);
    EXPECT_EQ(p.method, METHOD_RCME);
    EXPECT_EQ(p.solver, SOLVER_EIGHT_POINT);
    EXPECT_FALSE(p.localOptimization);
    EXPECT_EQ(p.ambiguityMargin, 0.0);
    EXPECT_EQ(p.maxRotationStdDeg, 0.0);
    EXPECT_EQ(p.maxTranslationStdDeg, 0.0);
    const Params defaults;
    EXPECT_TRUE(defaults.localOptimization);
    EXPECT_GT(defaults.ambiguityMargin, 0.0);
    EXPECT_EQ(p.maxIterations, defaults.maxIterations); // the rest: the defaults
    EXPECT_EQ(p.sigma, defaults.sigma);
}

TEST(Rcme_Standard, recover_pose_follows_opencv_conventions)
{
    const SyntheticScene scene = genericTestScene(3);
    Mat E, R, t, mask, covariance;
    Status status;
    const int count = recoverPose(scene.points1, scene.points2, scene.cameraMatrix, E, R, t,
                                  standardParams(), mask, status, covariance);
    ASSERT_EQ(status, STATUS_SUCCESS);
    EXPECT_EQ(R.size(), Size(3, 3));
    EXPECT_EQ(R.type(), CV_64F);
    EXPECT_EQ(t.size(), Size(1, 3));
    EXPECT_NEAR(cv::norm(t), 1.0, 1e-9);
    EXPECT_NEAR(determinant(R), 1.0, 1e-9);
    EXPECT_LT(cv::norm(R.t() * R - Mat::eye(3, 3, CV_64F)), 1e-9);
    EXPECT_EQ(mask.type(), CV_8U);
    EXPECT_EQ(mask.rows, scene.points1.rows);
    EXPECT_EQ(mask.cols, 1);
    EXPECT_EQ(countNonZero(mask), count);
    // E = [t]x R and cv::recoverPose agrees with our R, t from our E and mask.
    Mat tx = Mat(Matx33d(0, -t.at<double>(2), t.at<double>(1), t.at<double>(2), 0, -t.at<double>(0),
                         -t.at<double>(1), t.at<double>(0), 0));
    EXPECT_LT(cv::norm(E - tx * R), 1e-9);
    Mat Rcv, tcv, maskCv = mask.clone();
    cv::recoverPose(E, scene.points1, scene.points2, scene.cameraMatrix, Rcv, tcv, maskCv);
    EXPECT_LT(cv::norm(Rcv - R), 1e-6);
    EXPECT_LT(cv::norm(tcv - t), 1e-6);
    // The refined motion comes with its covariance, symmetric positive definite.
    ASSERT_EQ(covariance.size(), Size(5, 5));
    EXPECT_LT(cv::norm(covariance - covariance.t()), 1e-12 * cv::norm(covariance));
    Mat eigenvalues;
    eigen(covariance, eigenvalues);
    EXPECT_GT(eigenvalues.at<double>(4), 0.0);
}

TEST(Rcme_Standard, finds_the_true_inliers)
{
    const SyntheticScene scene = genericTestScene(5, 0.4, 400);
    Mat mask;
    Status status;
    const Mat F = findFundamentalMat(scene.points1, scene.points2, standardParams(), mask, status);
    ASSERT_EQ(status, STATUS_SUCCESS);
    ASSERT_EQ(F.size(), Size(3, 3));
    EXPECT_NEAR(cv::norm(F), 1.0, 1e-9);
    int truePositive = 0, falsePositive = 0;
    for (int i = 0; i < mask.rows; ++i) {
        truePositive += mask.at<uchar>(i) && scene.inlierMask.at<uchar>(i);
        falsePositive += mask.at<uchar>(i) && !scene.inlierMask.at<uchar>(i);
    }
    EXPECT_GT(truePositive, 0.9 * countNonZero(scene.inlierMask));
    EXPECT_LT(falsePositive, 0.05 * countNonZero(scene.inlierMask));
    // Every mask entry is 0 or 1, never 255 or other values.
    double maxValue = 0;
    minMaxLoc(mask, nullptr, &maxValue);
    EXPECT_EQ(maxValue, 1.0);
}

TEST(Rcme_Standard, same_seed_same_result_and_seed_matters)
{
    const SyntheticScene scene = genericTestScene(9, 0.6);
    Params params = standardParams(42);
    params.exactIterations = true;
    params.maxIterations = 200;
    params.refine = false;
    const Report a = estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
    const Report b = estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
    ASSERT_EQ(a.status, STATUS_SUCCESS);
    EXPECT_EQ(cv::norm(a.F, b.F, NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(a.mask, b.mask, NORM_INF), 0.0);
    params.randomGeneratorState = 43;
    const Report c = estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
    EXPECT_GT(cv::norm(a.F, c.F, NORM_INF), 0.0);
}

TEST(Rcme_Standard, exact_iterations_mode_runs_exactly_n)
{
    const SyntheticScene scene = genericTestScene(2, 0.8);
    Params params = standardParams();
    params.maxIterations = 300;
    const Report adaptive = estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
    EXPECT_LT(adaptive.iterations, 300); // w = 0.8 needs ~25 iterations at p = 0.99
    params.exactIterations = true;
    const Report exact = estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
    EXPECT_EQ(exact.iterations, 300);
}

TEST(Rcme_Standard, report_holds_everything)
{
    const SyntheticScene scene = genericTestScene(4);
    const Report r =
        estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, standardParams());
    ASSERT_EQ(r.status, STATUS_SUCCESS);
    EXPECT_TRUE(r.message.empty());
    EXPECT_EQ(r.F.size(), Size(3, 3));
    EXPECT_EQ(r.E.size(), Size(3, 3));
    EXPECT_EQ(r.R.size(), Size(3, 3));
    EXPECT_EQ(r.t.size(), Size(1, 3));
    EXPECT_EQ(r.covariance.size(), Size(5, 5));
    EXPECT_EQ(r.mask.rows, scene.points1.rows);
    EXPECT_EQ(r.inlierCount, countNonZero(r.mask));
    EXPECT_GT(r.iterations, 0);
    EXPECT_GE(r.timeSeconds, 0.0);
    EXPECT_TRUE(cvIsNaN(r.meanEntropy)); // only RCME computes entropies
    // F is consistent with K and E.
    const Mat K = scene.cameraMatrix, Kinv = K.inv();
    Mat F = Kinv.t() * r.E * Kinv;
    F /= cv::norm(F);
    EXPECT_LT(std::min(cv::norm(F - r.F), cv::norm(F + r.F)), 1e-9);
}

TEST(Rcme_Standard, calibrated_fundamental_has_equal_singular_values)
{
    const SyntheticScene scene = genericTestScene(6);
    Mat mask;
    Status status;
    const Mat F = findFundamentalMat(scene.points1, scene.points2, scene.cameraMatrix,
                                     standardParams(), mask, status);
    ASSERT_EQ(status, STATUS_SUCCESS);
    const Mat E = scene.cameraMatrix.t() * F * scene.cameraMatrix;
    Mat w;
    SVDecomp(E, w, noArray(), noArray());
    EXPECT_NEAR(w.at<double>(0), w.at<double>(1), 1e-9 * w.at<double>(0));
    EXPECT_LT(w.at<double>(2), 1e-9 * w.at<double>(0));
}

TEST(Rcme_Standard, threads_give_the_serial_results)
{
    std::vector<SyntheticScene> scenes;
    std::vector<Report> serial;
    for (int i = 0; i < 4; ++i) {
        scenes.push_back(genericTestScene(20 + i));
        serial.push_back(estimateRelativeMotion(scenes[i].points1, scenes[i].points2,
                                                scenes[i].cameraMatrix, standardParams(i)));
    }
    std::vector<Report> parallel(4);
    std::vector<std::thread> threads;
    for (int i = 0; i < 4; ++i)
        threads.emplace_back([&, i] {
            parallel[i] = estimateRelativeMotion(scenes[i].points1, scenes[i].points2,
                                                 scenes[i].cameraMatrix, standardParams(i));
        });
    for (auto& thread : threads)
        thread.join();
    for (int i = 0; i < 4; ++i) {
        ASSERT_EQ(parallel[i].status, serial[i].status);
        EXPECT_EQ(cv::norm(parallel[i].R, serial[i].R, NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(parallel[i].mask, serial[i].mask, NORM_INF), 0.0);
    }
}

TEST(Rcme_Standard, accepts_opencv_point_layouts)
{
    const SyntheticScene scene = genericTestScene(8);
    const Params params = standardParams();
    Mat reference;
    Status status;
    const Mat F = findFundamentalMat(scene.points1, scene.points2, params, reference, status);
    ASSERT_EQ(status, STATUS_SUCCESS);

    std::vector<Point2d> v1, v2;
    std::vector<Point2f> f1, f2;
    for (int i = 0; i < scene.points1.rows; ++i) {
        v1.emplace_back(scene.points1.at<double>(i, 0), scene.points1.at<double>(i, 1));
        v2.emplace_back(scene.points2.at<double>(i, 0), scene.points2.at<double>(i, 1));
        f1.emplace_back(v1.back());
        f2.emplace_back(v2.back());
    }
    const Mat nx1 = Mat(v1).clone(), nx1b = Mat(v2).clone();            // Nx1 CV_64FC2
    const Mat oneByN = nx1.reshape(2, 1), oneByNb = nx1b.reshape(2, 1); // 1xN CV_64FC2
    Mat mask;
    EXPECT_EQ(cv::norm(findFundamentalMat(v1, v2, params, mask, status), F, NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(findFundamentalMat(nx1, nx1b, params, mask, status), F, NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(findFundamentalMat(oneByN, oneByNb, params, mask, status), F, NORM_INF),
              0.0);
    EXPECT_EQ(mask.size(), Size(1, scene.points1.rows)); // Nx1 whatever the input layout
    // Non-continuous views (columns of a wider matrix) give the same estimate.
    Mat both;
    hconcat(scene.points1, scene.points2, both);
    EXPECT_FALSE(both.colRange(0, 2).isContinuous());
    EXPECT_EQ(
        cv::norm(findFundamentalMat(both.colRange(0, 2), both.colRange(2, 4), params, mask, status),
                 F, NORM_INF),
        0.0);
    // Float input: the same estimate up to float rounding.
    const Mat Ff = findFundamentalMat(f1, f2, params, mask, status);
    ASSERT_EQ(status, STATUS_SUCCESS);
    EXPECT_LT(std::min(cv::norm(Ff - F), cv::norm(Ff + F)), 1e-3);
}

TEST(Rcme_Standard, drop_in_signatures_match_opencv_usage)
{
    const SyntheticScene scene = genericTestScene(10);
    Mat mask;
    // Same call as cv::findFundamentalMat(p1, p2, FM_RANSAC, 3, 0.99, 1000, mask).
    const Mat F = cv::rcme::findFundamentalMat(scene.points1, scene.points2, FM_RANSAC, 3.0, 0.99,
                                               1000, mask);
    ASSERT_EQ(F.size(), Size(3, 3));
    EXPECT_EQ(mask.rows, scene.points1.rows);
    const Mat F2 = cv::rcme::findFundamentalMat(scene.points1, scene.points2, FM_RANSAC, 3.0, 0.99);
    EXPECT_EQ(F2.size(), Size(3, 3));
    // findEssentialMat + recoverPose as in OpenCV code.
    const Mat E = cv::rcme::findEssentialMat(scene.points1, scene.points2, scene.cameraMatrix,
                                             RANSAC, 0.999, 2.0, 1000, mask);
    ASSERT_EQ(E.size(), Size(3, 3));
    Mat R, t;
    const int inliers =
        cv::rcme::recoverPose(E, scene.points1, scene.points2, scene.cameraMatrix, R, t, mask);
    EXPECT_GT(inliers, 100);
    EXPECT_LT(compareMotion(R, t, scene.R, scene.t).rotationDeg, 1.0);
    // Focal / principal point forms.
    const double focal = scene.cameraMatrix.at<double>(0, 0);
    const Point2d pp(scene.cameraMatrix.at<double>(0, 2), scene.cameraMatrix.at<double>(1, 2));
    const Mat E2 = cv::rcme::findEssentialMat(scene.points1, scene.points2, focal, pp, RANSAC,
                                              0.999, 2.0, 1000, mask);
    ASSERT_EQ(E2.size(), Size(3, 3));
    Mat R2, t2;
    cv::rcme::recoverPose(E2, scene.points1, scene.points2, R2, t2, focal, pp, mask);
    EXPECT_LT(compareMotion(R2, t2, scene.R, scene.t).rotationDeg, 1.0);
}

TEST(Rcme_Standard, params_from_usac_params)
{
    UsacParams usac;
    usac.confidence = 0.95;
    usac.maxIterations = 123;
    usac.randomGeneratorState = 77;
    usac.threshold = 2.5;
    usac.sampler = SAMPLING_UNIFORM;
    const Params params(usac);
    EXPECT_EQ(params.confidence, 0.95);
    EXPECT_EQ(params.maxIterations, 123);
    EXPECT_EQ(params.randomGeneratorState, 77);
    EXPECT_EQ(params.threshold, 2.5);
    EXPECT_EQ(params.sampler, SAMPLER_UNIFORM);
    usac.sampler = SAMPLING_NAPSAC;
    EXPECT_THROW(Params{usac}, cv::Exception);
}

} // namespace
} // namespace opencv_test

namespace opencv_test {
namespace {

TEST(Rcme_Standard, local_optimization_gathers_more_inliers)
{
    // With the final refinement off, what the loop selects is what comes out: LO's refits of the
    // candidates recover more of the true inliers (measured: mean recall 0.49 -> 0.57).
    double recall[2] = {0, 0};
    const int runs = testRuns(20, 5);
    for (int seed = 0; seed < runs; ++seed) {
        const SyntheticScene scene = genericTestScene(seed, 0.4);
        for (int lo = 0; lo < 2; ++lo) {
            Params params = standardParams(seed);
            params.refine = false;
            params.localOptimization = lo == 1;
            const Report r =
                estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
            if (r.status != STATUS_SUCCESS)
                continue;
            int found = 0;
            for (int i = 0; i < r.mask.rows; ++i)
                found += r.mask.at<uchar>(i) && scene.inlierMask.at<uchar>(i);
            recall[lo] += static_cast<double>(found) / countNonZero(scene.inlierMask) / runs;
        }
    }
    if (kChecksStatistics) {
        EXPECT_GT(recall[1], recall[0] + 0.04);
    }
}

// Above kMaxIteratedPoints (20000) inliers the deciding fits iterate on an evenly spaced subset
// and the final estimate finishes on every point (doc/performance.md, "Large inputs"). 30000
// inliers take that path; the motion must stay as accurate as its reported uncertainty says,
// which is computed on all the inliers. (A fit left on the subset would be only sqrt(1.5) less
// accurate, which four seeds cannot tell apart: the mean below is printed, not checked.)
TEST(Rcme_Standard, large_inputs_are_refined_on_every_inlier)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.numPoints = 60000;
    sp.inlierRatio = 0.5;
    double normalizedSquares = 0;
    int dof = 0;
    const int seeds = testRuns(4, 2);
    for (int seed = 0; seed < seeds; ++seed) {
        sp.seed = 100 + seed;
        const SyntheticScene scene = generateScene(sp);
        Params params; // the defaults
        params.randomGeneratorState = seed;
        const Report report =
            estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
        ASSERT_EQ(report.status, STATUS_SUCCESS) << report.message;
        const int inliers = countNonZero(report.mask);
        EXPECT_GT(inliers, 27000);
        EXPECT_LT(inliers, 33000);
        const MotionError error = compareMotion(report.R, report.t, scene.R, scene.t);
        // The largest axis deviation bounds the rotation error's spread from above.
        double rotationStd = 0;
        minMaxLoc(report.rotationStdDeg, nullptr, &rotationStd);
        EXPECT_LT(error.rotationDeg, 4 * std::sqrt(3.0) * rotationStd);
        EXPECT_LT(error.translationDeg, 4 * std::sqrt(2.0) * report.translationStdDeg);
        normalizedSquares += std::pow(error.translationDeg / report.translationStdDeg, 2);
        dof += 2;
    }
    // E[chi^2_2 / 2] = 1 for errors as large as predicted; sqrt(1.5) times larger gives 1.5.
    std::cout << "translation error^2 / predicted variance, mean per dof: "
              << normalizedSquares / dof << std::endl;
}

// On a large set the final fit settles its band on the evenly spaced subset of the iterations
// and then takes three rounds on every point (components/gold_standard_refiner.cpp). The rounds
// move the model only part of the way each; four rounds on every point alone left this scene's
// translation 6.8 deg off with a reported standard deviation of 0.13 deg (53 of them), a success.
TEST(Rcme_Standard, a_large_final_fit_reaches_the_accuracy_it_reports)
{
    if (kSanitizedBuild) {
        // 200000 points take minutes under the sanitizers, and fewer do not take this path.
        std::printf("not run in a sanitizer build\n");
        return;
    }
    SceneParams sp; // the corridor
    sp.numPoints = 200000;
    sp.inlierRatio = 0.5;
    sp.seed = 1;
    const SyntheticScene scene = generateScene(sp);
    const Report report =
        estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, Params());
    ASSERT_EQ(report.status, STATUS_SUCCESS) << report.message;
    const MotionError error = compareMotion(report.R, report.t, scene.R, scene.t);
    double rotationStd = 0;
    minMaxLoc(report.rotationStdDeg, nullptr, &rotationStd);
    EXPECT_LT(error.rotationDeg, 4 * std::sqrt(3.0) * rotationStd);
    EXPECT_LT(error.translationDeg, 4 * std::sqrt(2.0) * report.translationStdDeg);
}

} // namespace
} // namespace opencv_test
