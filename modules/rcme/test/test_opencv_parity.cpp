// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Argument parity by differential test with the OpenCV the test is built with (4.6 standalone;
// 5.1, 4.14 and 4.6 in-tree): every OpenCV form of findFundamentalMat, findEssentialMat and
// recoverPose is called with the same valid and invalid arguments through cv:: and cv::rcme::. Both
// must accept or both must reject (with a cv::Exception), and on accepted input rcme's mask must
// have OpenCV's shape and type, except for the deliberate differences listed in kDeliberate
// (README, "Drop-in", says why).

#include "test_precomp.hpp"

#include <algorithm>
#include <functional>
#include <iostream>
#include <utility>

namespace opencv_test {
namespace {

// The same call through either namespace: a generic lambda takes one of these and calls
// api.fundamental(...), api.essential(...), api.pose(...), resolved among that namespace's
// overloads exactly as user code would be.
#define RCME_PARITY_API(Name, NS)                                                                  \
    struct Name                                                                                    \
    {                                                                                              \
        template <class... A> cv::Mat fundamental(A&&... a) const                                  \
        {                                                                                          \
            return NS::findFundamentalMat(std::forward<A>(a)...);                                  \
        }                                                                                          \
        template <class... A>                                                                      \
        auto essential(A&&... a) const -> decltype(NS::findEssentialMat(std::forward<A>(a)...))    \
        {                                                                                          \
            return NS::findEssentialMat(std::forward<A>(a)...);                                    \
        }                                                                                          \
        template <class... A> int pose(A&&... a) const                                             \
        {                                                                                          \
            return NS::recoverPose(std::forward<A>(a)...);                                         \
        }                                                                                          \
    };
RCME_PARITY_API(RcmeApi, cv::rcme)
#if CV_VERSION_MAJOR < 5
RCME_PARITY_API(OpenCVApi, cv)
#else
RCME_PARITY_API(OpenCVDeclaredApi, cv)
// OpenCV 5 removed the two findEssentialMat forms without maxIters, which ran 1000 iterations in
// 4.x; rcme keeps them, so that 4.x code keeps compiling. Their cases compare with the form
// OpenCV 5 kept, with maxIters = 1000: the call 4.x code has to be rewritten to.
struct OpenCVApi : OpenCVDeclaredApi
{
    using OpenCVDeclaredApi::essential;
    cv::Mat essential(const Mat& p1, const Mat& p2, const Mat& K, int method, double prob,
                      double threshold, Mat& mask) const
    {
        return cv::findEssentialMat(p1, p2, K, method, prob, threshold, 1000, mask);
    }
    cv::Mat essential(const Mat& p1, const Mat& p2, double focal, Point2d pp, int method,
                      double prob, double threshold, Mat& mask) const
    {
        return cv::findEssentialMat(p1, p2, focal, pp, method, prob, threshold, 1000, mask);
    }
};
#endif
#undef RCME_PARITY_API

enum class Outcome
{
    Accept,
    Reject, //!< cv::Exception
    OtherException,
    NotRun //!< OpenCV crashes on this input, so it is not called
};

const char* outcomeName(Outcome o)
{
    switch (o) {
    case Outcome::Accept:
        return "accept";
    case Outcome::Reject:
        return "reject";
    case Outcome::OtherException:
        return "other exception";
    case Outcome::NotRun:
        break;
    }
    return "crashe"; // + "s"
}

struct CallResult
{
    Outcome outcome = Outcome::Accept;
    cv::Mat mask;
    std::string what;
};

struct Case
{
    std::string name;
    std::function<void(cv::Mat&)> opencv, rcme;
};

template <class Call> CallResult runCall(const Call& call)
{
    CallResult r;
    try {
        call(r.mask);
    } catch (const cv::Exception& e) {
        r.outcome = Outcome::Reject;
        r.what = e.what();
    } catch (const std::exception& e) {
        r.outcome = Outcome::OtherException;
        r.what = e.what();
    }
    return r;
}

// A deliberate difference: what each side does, and why (the README's table says the same).
struct Deliberate
{
    const char* prefix; //!< applies to the cases whose name starts with it
    Outcome opencv, rcme;
    const char* why;
};

const Deliberate kDeliberate[] = {
    {"F method 99", Outcome::Accept, Outcome::Reject,
     "OpenCV runs LMedS for any unknown method value; rcme rejects it, naming `method`"},
    {"E method 99", Outcome::Accept, Outcome::Reject,
     "OpenCV runs LMedS for any unknown method value; rcme rejects it, naming `method`"},
    {"F nan point", Outcome::Accept, Outcome::Reject,
     "OpenCV estimates from non-finite coordinates; rcme rejects them, naming the point"},
#if CV_VERSION_MAJOR < 5 // OpenCV 5.1 rejects it too (an assertion in its 5-point solver)
    {"E nan point", Outcome::Accept, Outcome::Reject,
     "OpenCV estimates from non-finite coordinates; rcme rejects them, naming the point"},
#endif
    {"E negative focal", Outcome::Accept, Outcome::Reject,
     "a negative focal length lets points behind the camera pass cheirality: a wrong motion"},
#if CV_VERSION_MAJOR < 5 // OpenCV 5.1 rejects it too (an assertion in its 5-point solver)
    {"E focal form focal 0", Outcome::Accept, Outcome::Reject,
     "OpenCV divides by a zero focal length; rcme rejects it, naming `focal`"},
#else
    {"E points of depth 0", Outcome::Reject, Outcome::Accept,
     "OpenCV 5.1's 5-point solver asserts (solvePoly) on the 8-bit points, many of them "
     "identical after saturation; rcme answers as with OpenCV 4.x, from the points it can use"},
    {"R int32 mask", Outcome::Accept, Outcome::Reject,
     "OpenCV 5.1 takes an int32 input mask; rcme keeps OpenCV 4.x's rule (CV_8U) and names "
     "`mask`"},
#endif
    {"E focal form focal -5", Outcome::Accept, Outcome::Reject,
     "a negative focal length lets points behind the camera pass cheirality: a wrong motion"},
    {"E usac NAPSAC", Outcome::NotRun, Outcome::Accept,
     "OpenCV 4.6's findEssentialMat with SAMPLING_NAPSAC crashes (SIGSEGV); rcme samples "
     "uniformly"},
    {"F usac few points", Outcome::Reject, Outcome::Accept,
     "OpenCV's USAC asserts on fewer points than a sample; rcme returns an empty F (not enough "
     "points), as every other form of both does"},
    {"R empty E", Outcome::Reject, Outcome::Accept,
     "what findEssentialMat returns on failure: rcme answers 0 points, R = I, t = 0, a zero mask, "
     "so that OpenCV code keeps running on a bad frame"},
};

const Deliberate* deliberate(const std::string& caseName)
{
    for (const Deliberate& d : kDeliberate)
        if (caseName.rfind(d.prefix, 0) == 0)
            return &d;
    return nullptr;
}

// Cases where both accept but OpenCV's mask has another layout: rcme's is always Nx1 CV_8U, of
// zeros on failure (OpenCV leaves it unwritten when it returns early, and FM_7POINT/FM_8POINT
// give 1xN). Code reading mask.at<uchar>(i) for i < N works on both.
bool maskLayoutMayDiffer(const std::string& caseName)
{
    return caseName.find("few") != std::string::npos ||
           caseName.find("FM_7POINT") != std::string::npos ||
           caseName.find("FM_8POINT") != std::string::npos ||
           caseName.find("usac maxIterations") != std::string::npos;
}

template <class F> Case makeCase(std::string caseName, F f)
{
    return {std::move(caseName), [f](cv::Mat& mask) { f(OpenCVApi(), mask); },
            [f](cv::Mat& mask) { f(RcmeApi(), mask); }};
}

std::vector<Case> parityCases()
{
    // Outlier-free, so that OpenCV's RANSAC stops early where it can (its 5-point solver is the
    // cost of this test); the cases that cannot converge run 50 iterations where the form
    // takes maxIters.
    const SyntheticScene s = genericTestScene(3, 1.0, 60);
    const Mat p1 = s.points1, p2 = s.points2, K = s.cameraMatrix, E = s.E;
    const Point2d pp(K.at<double>(0, 2), K.at<double>(1, 2));
    const double focal = K.at<double>(0, 0);
    const Mat few1 = p1.rowRange(0, 4), few2 = p2.rowRange(0, 4);
    const Mat shorter = p2.rowRange(0, 40);
    Mat nanPoints = p1.clone();
    nanPoints.at<double>(5, 1) = std::numeric_limits<double>::quiet_NaN();
    Mat negativeFocal = K.clone();
    negativeFocal.at<double>(0, 0) = -focal;
    Mat Kint;
    K.convertTo(Kint, CV_32S);
    const Mat distortion = Mat(Matx<double, 1, 5>(0.01, -0.001, 0, 0, 0));
    const Mat badDistortion(1, 3, CV_64F, Scalar(0));
    const Mat homogeneous1(p1.rows, 3, CV_64F, Scalar(1)), homogeneous2 = homogeneous1.clone();
    p1.copyTo(homogeneous1.colRange(0, 2));
    p2.copyTo(homogeneous2.colRange(0, 2));
    const double nan = std::numeric_limits<double>::quiet_NaN();

    std::vector<Case> cases;
    const auto addCase = [&cases](std::string n, auto f) {
        cases.push_back(makeCase(std::move(n), f));
    };

    // --- findFundamentalMat
    const std::pair<const char*, int> fundamentalFlags[] = {{"FM_7POINT", FM_7POINT},
                                                            {"FM_8POINT", FM_8POINT},
                                                            {"FM_LMEDS", FM_LMEDS},
                                                            {"FM_RANSAC", FM_RANSAC},
                                                            {"RHO", RHO},
                                                            {"USAC_DEFAULT", USAC_DEFAULT},
                                                            {"USAC_PARALLEL", USAC_PARALLEL},
                                                            {"USAC_FM_8PTS", USAC_FM_8PTS},
                                                            {"USAC_FAST", USAC_FAST},
                                                            {"USAC_ACCURATE", USAC_ACCURATE},
                                                            {"USAC_PROSAC", USAC_PROSAC},
                                                            {"USAC_MAGSAC", USAC_MAGSAC},
                                                            {"99", 99}};
    for (const auto& flag : fundamentalFlags) {
        const int m = flag.second;
        addCase(std::string("F method ") + flag.first,
                [=](auto api, Mat& k) { api.fundamental(p1, p2, m, 3., 0.99, 1000, k); });
    }
    for (int iters : {0, -1, 1})
        addCase("F maxIters " + std::to_string(iters),
                [=](auto api, Mat& k) { api.fundamental(p1, p2, FM_RANSAC, 3., 0.99, iters, k); });
    for (double c : {0.0, 1.0, -0.5, 1.5, nan}) {
        addCase("F confidence " + std::to_string(c),
                [=](auto api, Mat& k) { api.fundamental(p1, p2, FM_RANSAC, 3., c, 1000, k); });
        addCase("F defaults form confidence " + std::to_string(c),
                [=](auto api, Mat& k) { api.fundamental(p1, p2, FM_RANSAC, 3., c, k); });
        addCase("F mask-first form confidence " + std::to_string(c),
                [=](auto api, Mat& k) { api.fundamental(p1, p2, k, FM_RANSAC, 3., c); });
    }
    for (double t : {0.0, -1.0, nan})
        addCase("F threshold " + std::to_string(t),
                [=](auto api, Mat& k) { api.fundamental(p1, p2, FM_RANSAC, t, 0.99, 1000, k); });
    addCase("F defaults form",
            [=](auto api, Mat& k) { api.fundamental(p1, p2, FM_RANSAC, 3., .99, k); });
    addCase("F mask-first form", [=](auto api, Mat& k) { api.fundamental(p1, p2, k); });
    addCase("F empty",
            [=](auto api, Mat& k) { api.fundamental(Mat(), Mat(), FM_RANSAC, 3., .99, k); });
    addCase("F mismatched", [=](auto api, Mat& k) { api.fundamental(p1, shorter, k); });
    addCase("F few points", [=](auto api, Mat& k) { api.fundamental(few1, few2, k); });
    addCase("F nan point", [=](auto api, Mat& k) { api.fundamental(nanPoints, p2, k); });
    addCase("F homogeneous points",
            [=](auto api, Mat& k) { api.fundamental(homogeneous1, homogeneous2, k); });
    for (int depth : {CV_8U, CV_16S, CV_32S, CV_16F, CV_32F})
        addCase("F points of depth " + std::to_string(depth), [=](auto api, Mat& k) {
            Mat a, b;
            p1.convertTo(a, depth);
            p2.convertTo(b, depth);
            api.fundamental(a, b, k);
        });
    addCase("F two columns of two channels", [=](auto api, Mat& k) {
        api.fundamental(Mat(60, 2, CV_64FC2, Scalar::all(1)), Mat(60, 2, CV_64FC2, Scalar::all(2)),
                        k);
    });

    // --- the UsacParams forms
    const auto usacWith = [](const std::function<void(UsacParams&)>& set) {
        UsacParams u;
        set(u);
        return u;
    };
    std::vector<std::pair<std::string, UsacParams>> usacs = {
        {"default", UsacParams()},
        {"confidence 0", usacWith([](UsacParams& u) { u.confidence = 0; })},
        {"confidence 1.5", usacWith([](UsacParams& u) { u.confidence = 1.5; })},
        {"maxIterations 0", usacWith([](UsacParams& u) { u.maxIterations = 0; })},
        {"maxIterations -1", usacWith([](UsacParams& u) { u.maxIterations = -1; })},
        {"threshold 0", usacWith([](UsacParams& u) { u.threshold = 0; })},
        {"threshold -1", usacWith([](UsacParams& u) { u.threshold = -1; })},
        {"NAPSAC", usacWith([](UsacParams& u) { u.sampler = SAMPLING_NAPSAC; })},
        {"PROSAC", usacWith([](UsacParams& u) { u.sampler = SAMPLING_PROSAC; })},
        {"MAGSAC score", usacWith([](UsacParams& u) { u.score = SCORE_METHOD_MAGSAC; })},
    };
    for (const auto& u : usacs) {
        const UsacParams params = u.second;
        addCase("F usac " + u.first, [=](auto api, Mat& k) { api.fundamental(p1, p2, k, params); });
        addCase("E usac " + u.first, [=](auto api, Mat& k) {
            api.essential(p1, p2, K, K, distortion, distortion, k, params);
        });
    }
    addCase("F usac empty",
            [=](auto api, Mat& k) { api.fundamental(Mat(), Mat(), k, UsacParams()); });
    addCase("F usac mismatched",
            [=](auto api, Mat& k) { api.fundamental(p1, shorter, k, UsacParams()); });
    addCase("F usac few points",
            [=](auto api, Mat& k) { api.fundamental(few1, few2, k, UsacParams()); });

    // --- findEssentialMat
    const std::pair<const char*, int> essentialFlags[] = {{"LMEDS", LMEDS},
                                                          {"RANSAC", RANSAC},
                                                          {"RHO", RHO},
                                                          {"USAC_DEFAULT", USAC_DEFAULT},
                                                          {"USAC_PARALLEL", USAC_PARALLEL},
                                                          {"USAC_FAST", USAC_FAST},
                                                          {"USAC_ACCURATE", USAC_ACCURATE},
                                                          {"USAC_PROSAC", USAC_PROSAC},
                                                          {"USAC_MAGSAC", USAC_MAGSAC},
                                                          {"99", 99}};
    for (const auto& flag : essentialFlags) {
        const int m = flag.second;
        addCase(std::string("E method ") + flag.first,
                [=](auto api, Mat& k) { api.essential(p1, p2, K, m, 0.999, 1., 50, k); });
    }
    for (int iters : {0, -1})
        addCase("E maxIters " + std::to_string(iters),
                [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, 0.999, 1., iters, k); });
    for (double c : {0.0, 1.0, -0.5, 1.5, nan}) {
        addCase("E prob " + std::to_string(c),
                [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, c, 1., 50, k); });
        addCase("E no-maxIters form prob " + std::to_string(c),
                [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, c, 1., k); });
        addCase("E focal form prob " + std::to_string(c),
                [=](auto api, Mat& k) { api.essential(p1, p2, focal, pp, RANSAC, c, 1., 50, k); });
        addCase("E focal no-maxIters form prob " + std::to_string(c),
                [=](auto api, Mat& k) { api.essential(p1, p2, focal, pp, RANSAC, c, 1., k); });
        addCase("E two cameras prob " + std::to_string(c), [=](auto api, Mat& k) {
            api.essential(p1, p2, K, distortion, K, distortion, RANSAC, c, 1., k);
        });
    }
    for (double t : {0.0, -1.0, nan}) {
        addCase("E threshold " + std::to_string(t),
                [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, 0.999, t, 50, k); });
        addCase("E two cameras threshold " + std::to_string(t), [=](auto api, Mat& k) {
            api.essential(p1, p2, K, distortion, K, distortion, RANSAC, 0.999, t, k);
        });
    }
    addCase("E defaults",
            [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, 0.999, 1., 50, k); });
    addCase("E documentation form",
            [=](auto api, Mat& k) { api.essential(p1, p2, K, RANSAC, 0.999, 1.0, k); });
    addCase("E focal form defaults",
            [=](auto api, Mat& k) { api.essential(p1, p2, focal, pp, RANSAC, 0.999, 1., 50, k); });
    addCase("E focal form focal 0",
            [=](auto api, Mat& k) { api.essential(p1, p2, 0.0, pp, RANSAC, 0.999, 1., 50, k); });
    addCase("E focal form focal -5",
            [=](auto api, Mat& k) { api.essential(p1, p2, -5.0, pp, RANSAC, 0.999, 1., 50, k); });
    addCase("E two cameras no distortion", [=](auto api, Mat& k) {
        api.essential(p1, p2, K, noArray(), K, noArray(), RANSAC, 0.999, 1., k);
    });
    addCase("E two cameras bad distortion", [=](auto api, Mat& k) {
        api.essential(p1, p2, K, badDistortion, K, badDistortion, RANSAC, 0.999, 1., k);
    });
    addCase("E empty",
            [=](auto api, Mat& k) { api.essential(Mat(), Mat(), K, RANSAC, 0.999, 1., 50, k); });
    addCase("E mismatched",
            [=](auto api, Mat& k) { api.essential(p1, shorter, K, RANSAC, 0.999, 1., 50, k); });
    addCase("E few points",
            [=](auto api, Mat& k) { api.essential(few1, few2, K, RANSAC, 0.999, 1., 50, k); });
    addCase("E nan point",
            [=](auto api, Mat& k) { api.essential(nanPoints, p2, K, RANSAC, 0.999, 1., 50, k); });
    addCase("E empty K",
            [=](auto api, Mat& k) { api.essential(p1, p2, Mat(), RANSAC, 0.999, 1., 50, k); });
    addCase("E 3x4 K", [=](auto api, Mat& k) {
        api.essential(p1, p2, Mat::eye(3, 4, CV_64F), RANSAC, 0.999, 1., 50, k);
    });
    addCase("E int32 K",
            [=](auto api, Mat& k) { api.essential(p1, p2, Kint, RANSAC, 0.999, 1., 50, k); });
    addCase("E negative focal K", [=](auto api, Mat& k) {
        api.essential(p1, p2, negativeFocal, RANSAC, 0.999, 1., 50, k);
    });
    addCase("E three columns", [=](auto api, Mat& k) {
        api.essential(homogeneous1, homogeneous2, K, RANSAC, 0.999, 1., 50, k);
    });
    for (int depth : {CV_8U, CV_16S, CV_32S, CV_16F, CV_32F})
        addCase("E points of depth " + std::to_string(depth), [=](auto api, Mat& k) {
            Mat a, b;
            p1.convertTo(a, depth);
            p2.convertTo(b, depth);
            api.essential(a, b, K, RANSAC, 0.999, 1., 50, k);
        });

    // --- recoverPose
    addCase("R from E", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(E, p1, p2, K, R, t, k);
    });
    addCase("R from E focal form", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(E, p1, p2, R, t, focal, pp, k);
    });
    for (double d : {50.0, 0.0, -1.0})
        addCase("R distanceThresh " + std::to_string(d), [=](auto api, Mat& k) {
            Mat R, t, points;
            api.pose(E, p1, p2, K, R, t, d, k, points);
        });
    addCase("R empty E", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(Mat(), p1, p2, K, R, t, k);
    });
    addCase("R zero E", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(Mat::zeros(3, 3, CV_64F), p1, p2, K, R, t, k);
    });
    addCase("R 3x9 E", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(Mat::zeros(3, 9, CV_64F), p1, p2, K, R, t, k);
    });
    addCase("R wrong mask size", [=](auto api, Mat& k) {
        k = Mat(61, 1, CV_8U, Scalar(1));
        Mat R, t;
        api.pose(E, p1, p2, K, R, t, k);
    });
    addCase("R int32 mask", [=](auto api, Mat& k) {
        k = Mat(60, 1, CV_32S, Scalar(1));
        Mat R, t;
        api.pose(E, p1, p2, K, R, t, k);
    });
    addCase("R empty points", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(E, Mat(), Mat(), K, R, t, k);
    });
    addCase("R mismatched", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(E, p1, shorter, K, R, t, k);
    });
    addCase("R few points", [=](auto api, Mat& k) {
        Mat R, t;
        api.pose(E, few1, few2, K, R, t, k);
    });
    for (double c : {0.999, 0.0, 1.5})
        addCase("R two cameras prob " + std::to_string(c), [=](auto api, Mat& k) {
            Mat e, R, t;
            api.pose(p1, p2, K, distortion, K, distortion, e, R, t, RANSAC, c, 1.0, k);
        });
    addCase("R two cameras defaults", [=](auto api, Mat& k) {
        Mat e, R, t;
        api.pose(p1, p2, K, distortion, K, distortion, e, R, t, RANSAC, 0.999, 1.0, k);
    });
    addCase("R two cameras mismatched", [=](auto api, Mat& k) {
        Mat e, R, t;
        api.pose(p1, shorter, K, distortion, K, distortion, e, R, t, RANSAC, 0.999, 1.0, k);
    });
    return cases;
}

TEST(Rcme_OpenCVParity, both_accept_or_both_reject_and_masks_have_opencvs_layout)
{
    const std::vector<Case> cases = parityCases();
    int compared = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Deliberate* d = deliberate(c.name);
        const CallResult rc = runCall(c.rcme);
        EXPECT_NE(rc.outcome, Outcome::OtherException) << rc.what;
        if (d && d->opencv == Outcome::NotRun) {
            EXPECT_EQ(outcomeName(rc.outcome), std::string(outcomeName(d->rcme))) << rc.what;
            continue;
        }
        const CallResult cv = runCall(c.opencv);
        if (d) {
            EXPECT_EQ(outcomeName(cv.outcome), std::string(outcomeName(d->opencv))) << cv.what;
            EXPECT_EQ(outcomeName(rc.outcome), std::string(outcomeName(d->rcme))) << rc.what;
            continue;
        }
        ++compared;
        EXPECT_EQ(outcomeName(rc.outcome), std::string(outcomeName(cv.outcome)))
            << "OpenCV: " << cv.what << "\nrcme: " << rc.what;
        if (cv.outcome != Outcome::Accept || rc.outcome != Outcome::Accept)
            continue;
        if (!cv.mask.empty() && !maskLayoutMayDiffer(c.name)) {
            EXPECT_EQ(rc.mask.size(), cv.mask.size());
            EXPECT_EQ(rc.mask.type(), cv.mask.type());
        } else if (!rc.mask.empty()) { // rcme's own layout, always written
            EXPECT_EQ(rc.mask.cols, 1);
            EXPECT_EQ(rc.mask.type(), CV_8U);
        }
    }
    EXPECT_GT(compared, 100);
}

TEST(Rcme_OpenCVParity, every_deliberate_difference_has_a_case)
{
    const std::vector<Case> cases = parityCases();
    for (const Deliberate& d : kDeliberate) {
        const bool covered = std::any_of(cases.begin(), cases.end(), [&](const Case& c) {
            return c.name.rfind(d.prefix, 0) == 0;
        });
        EXPECT_TRUE(covered) << d.prefix;
        std::cout << "deliberate difference: " << d.prefix << " -- OpenCV " << outcomeName(d.opencv)
                  << "s, rcme " << outcomeName(d.rcme) << "s: " << d.why << "\n";
    }
}

TEST(Rcme_OpenCVParity, recover_pose_of_an_empty_e_is_a_standing_camera)
{
    const SyntheticScene s = genericTestScene(4, 0.7, 60);
    Mat R(3, 3, CV_64F, Scalar(5)), t(3, 1, CV_64F, Scalar(5)), mask, points(1, 1, CV_64F);
    for (const Mat& E : {Mat(), Mat(Mat::zeros(3, 3, CV_64F))}) {
        EXPECT_EQ(cv::rcme::recoverPose(E, s.points1, s.points2, s.cameraMatrix, R, t, 50.0, mask,
                                        points),
                  0);
        EXPECT_EQ(cv::norm(R, Mat::eye(3, 3, CV_64F), NORM_INF), 0.);
        EXPECT_EQ(cv::norm(t, NORM_INF), 0.);
        ASSERT_EQ(mask.size(), Size(1, 60));
        EXPECT_EQ(countNonZero(mask), 0);
        EXPECT_TRUE(points.empty());
    }
    // The two-camera form on points with no motion in them: 0, a standing camera, E empty.
    Mat E, randomPoints(60, 2, CV_64F);
    theRNG().state = 7;
    randu(randomPoints, 0, 640);
    Mat shuffled = randomPoints.clone();
    randu(shuffled, 0, 640);
    EXPECT_EQ(cv::rcme::recoverPose(randomPoints, shuffled, s.cameraMatrix, noArray(),
                                    s.cameraMatrix, noArray(), E, R, t, RANSAC, 0.999, 1.0, mask),
              0);
    EXPECT_TRUE(E.empty());
    EXPECT_EQ(cv::norm(R, Mat::eye(3, 3, CV_64F), NORM_INF), 0.);
    EXPECT_EQ(countNonZero(mask), 0);
}

// A pure rotation (with K) has no E: the E forms answer "nothing found" (empty E, zero mask, as
// the README promises), and the two-camera recoverPose returns the rotation with t = 0 and its
// inliers (a turn on the spot is a motion OpenCV code can use).
TEST(Rcme_OpenCVParity, a_pure_rotation_has_no_e_and_recover_pose_keeps_its_rotation)
{
    const SyntheticScene s = testScene(SCENE_PURE_ROTATION, 1);
    const int n = s.points1.rows;
    const double kThreshold = 2.0; // the scene's noise is 1 px: the 95 % band
    Mat mask;
    EXPECT_TRUE(cv::rcme::findEssentialMat(s.points1, s.points2, s.cameraMatrix, RANSAC, 0.999,
                                           kThreshold, mask)
                    .empty());
    ASSERT_EQ(mask.size(), Size(1, n));
    EXPECT_EQ(countNonZero(mask), 0);
    EXPECT_TRUE(cv::rcme::findEssentialMat(s.points1, s.points2, s.cameraMatrix, noArray(),
                                           s.cameraMatrix, noArray(), RANSAC, 0.999, kThreshold,
                                           mask)
                    .empty());
    EXPECT_EQ(countNonZero(mask), 0);

    Mat E, R, t;
    const int inliers =
        cv::rcme::recoverPose(s.points1, s.points2, s.cameraMatrix, noArray(), s.cameraMatrix,
                              noArray(), E, R, t, RANSAC, 0.999, kThreshold, mask);
    EXPECT_GT(inliers, n / 3);
    EXPECT_EQ(countNonZero(mask), inliers);
    EXPECT_TRUE(E.empty());
    const Mat unit = Mat(Vec3d(1, 0, 0));
    EXPECT_LT(compareMotion(R, unit, s.R, unit).rotationDeg, 0.3);
    ASSERT_EQ(t.size(), Size(1, 3));
    EXPECT_EQ(countNonZero(t), 0);
}

TEST(Rcme_OpenCVParity, new_forms_agree_with_opencv_on_a_clean_pair)
{
    const SyntheticScene s = genericTestScene(5, 1.0, 80);
    const Mat K = s.cameraMatrix;
    // Distorted pixels, so that the two-camera forms must undistort to find the motion.
    const Mat distortion = Mat(Matx<double, 1, 5>(-0.05, 0.01, 0, 0, 0));
    std::vector<Point3d> rays1, rays2;
    Mat u1, u2;
    undistortPoints(s.points1.reshape(2), u1, K, noArray());
    undistortPoints(s.points2.reshape(2), u2, K, noArray());
    convertPointsToHomogeneous(u1, rays1);
    convertPointsToHomogeneous(u2, rays2);
    Mat d1, d2;
    projectPoints(rays1, Vec3d(), Vec3d(), K, distortion, d1);
    projectPoints(rays2, Vec3d(), Vec3d(), K, distortion, d2);
    Mat E, R, t, mask;
    const int inliers = cv::rcme::recoverPose(d1, d2, K, distortion, K, distortion, E, R, t, RANSAC,
                                              0.999, 3.0, mask); // 3 sigma
    // As many as the true E puts closer than 50 baselines in front of both cameras.
    Mat Rtrue, ttrue;
    const int reachable = cv::rcme::recoverPose(s.E, s.points1, s.points2, K, Rtrue, ttrue);
    EXPECT_GE(inliers, reachable * 9 / 10);
    EXPECT_LT(compareMotion(R, t, s.R, s.t).rotationDeg, 0.5);
    const Mat E6 =
        cv::rcme::findEssentialMat(d1, d2, K, K, distortion, distortion, mask, UsacParams());
    ASSERT_FALSE(E6.empty());

    // Triangulated points: those of cv::recoverPose for the same E, up to the homogeneous scale.
    Mat Rc, tc, maskCv, pointsCv, Rr, tr, maskRc, pointsRc;
    cv::recoverPose(s.E, s.points1, s.points2, K, Rc, tc, 50.0, maskCv, pointsCv);
    cv::rcme::recoverPose(s.E, s.points1, s.points2, K, Rr, tr, 50.0, maskRc, pointsRc);
    EXPECT_EQ(countNonZero((maskCv != 0) != (maskRc != 0)), 0); // OpenCV's mask is 0/255 here
    ASSERT_EQ(pointsRc.size(), pointsCv.size());
    ASSERT_EQ(pointsRc.type(), pointsCv.type());
    for (int i = 0; i < pointsRc.cols; ++i) {
        const Mat a = pointsRc.col(i) / pointsRc.at<double>(3, i);
        const Mat b = pointsCv.col(i) / pointsCv.at<double>(3, i);
        EXPECT_LT(cv::norm(a, b, NORM_INF), 1e-6) << i;
    }
}

} // namespace
} // namespace opencv_test
