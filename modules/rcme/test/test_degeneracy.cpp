// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Scenes whose motion the data cannot determine: every point on one plane, or a camera that only
// rotates. Each method must say so (degenerate status) instead of returning one of the many F
// that fit, calibrated or not; with Params::degeneracyTest off the same data give a "success",
// which shows that the test is what catches them.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS
#include "components/homography_comparison.hpp"
#include "framework/component_factories.hpp"
#include "framework/components.hpp"
#include "framework/estimator_factory.hpp"
#include "framework/ransac_loop.hpp"
#include "framework/refinement.hpp"
#include "geometry/epipolar.hpp"
#include "test_internal_helpers.hpp"

#include <opencv2/core/eigen.hpp>
#endif

namespace opencv_test {
namespace {

enum class Degeneracy
{
    Plane,
    PureRotation
};

struct TwoViews
{
    Mat points1, points2, K;
    Mat R, t; //!< the true motion, x2 = R x1 + t (t zero for a pure rotation)
};

// Half inliers (sigma 1 px), half uniform outliers, 640x480, f = 500, as the other scenes.
TwoViews degenerateScene(Degeneracy kind, int seed)
{
    cv::RNG rng(static_cast<uint64>(seed) + 1);
    const Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
    Matx33d R;
    Rodrigues(Vec3d(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)), R);
    const Vec3d t = kind == Degeneracy::Plane ? Vec3d(1.0, 0.1, 0.2) : Vec3d(0, 0, 0);
    const Vec3d planeNormal = normalize(Vec3d(0.1, -0.2, 1.0));
    const double planeDistance = 8.0;

    constexpr int kPoints = 500;
    TwoViews views;
    views.K = Mat(K);
    views.R = Mat(R);
    views.t = Mat(t);
    projectTwoViews(
        rng, K, R, t, Size(640, 480), 1.0, kPoints / 2, kPoints,
        [&](const Vec3d& ray) {
            return kind == Degeneracy::Plane ? planeDistance / ray.dot(planeNormal)
                                             : rng.uniform(4.0, 20.0);
        },
        views.points1, views.points2);
    return views;
}

// Median Sampson distance (px) of the first `count` correspondences (the scene's inliers).
double medianSampson(const Mat& F, const TwoViews& v, int count)
{
    const Matx33d f(F);
    std::vector<double> d;
    for (int i = 0; i < count; ++i) {
        const Vec3d x1(v.points1.at<double>(i, 0), v.points1.at<double>(i, 1), 1.0);
        const Vec3d x2(v.points2.at<double>(i, 0), v.points2.at<double>(i, 1), 1.0);
        const Vec3d l2 = f * x1, l1 = f.t() * x2;
        const double e = x2.dot(l2);
        d.push_back(std::abs(e) /
                    std::sqrt(l2[0] * l2[0] + l2[1] * l2[1] + l1[0] * l1[0] + l1[1] * l1[1]));
    }
    std::nth_element(d.begin(), d.begin() + count / 2, d.end());
    return d[static_cast<size_t>(count / 2)];
}

TEST(Rcme_Rejected, a_degenerate_scene_reports_the_rejected_f_that_fits_its_inliers)
{
    for (int seed = 0; seed < 2; ++seed) {
        const TwoViews v = degenerateScene(Degeneracy::Plane, seed);
        Params params;
        params.randomGeneratorState = seed;
        const Report r = estimateRelativeMotion(v.points1, v.points2, noArray(), params);
        ASSERT_EQ(r.status, STATUS_DEGENERATE_CONFIGURATION) << seed;
        EXPECT_TRUE(r.F.empty()) << seed;
        ASSERT_EQ(r.rejectedF.size(), Size(3, 3)) << seed;
        EXPECT_NEAR(cv::norm(r.rejectedF), 1.0, 1e-9) << seed;
        EXPECT_LT(medianSampson(r.rejectedF, v, v.points1.rows / 2), 2.0) << seed;
        EXPECT_TRUE(r.rejectedR.empty() && r.rejectedT.empty()) << seed; // no K, no motion
    }
}

TEST(Rcme_Rejected, poor_quality_input_reports_its_most_supported_hypothesis_with_a_motion)
{
    cv::RNG rng(7);
    Mat p1(300, 2, CV_64F), p2(300, 2, CV_64F);
    rng.fill(p1, RNG::UNIFORM, 0, 640);
    rng.fill(p2, RNG::UNIFORM, 0, 640);
    const Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
    for (Method method : {METHOD_STANDARD, METHOD_PRCME}) {
        Params params;
        params.method = method;
        params.maxIterations = 200;
        const Report r = estimateRelativeMotion(p1, p2, Mat(K), params);
        ASSERT_EQ(r.status, STATUS_POOR_QUALITY_INPUT) << static_cast<int>(method);
        EXPECT_TRUE(r.F.empty() && r.R.empty() && r.t.empty()) << static_cast<int>(method);
        ASSERT_EQ(r.rejectedF.size(), Size(3, 3)) << static_cast<int>(method);
        ASSERT_EQ(r.rejectedR.size(), Size(3, 3)) << static_cast<int>(method);
        ASSERT_EQ(r.rejectedT.size(), Size(1, 3)) << static_cast<int>(method);
        EXPECT_NEAR(determinant(r.rejectedR), 1.0, 1e-9) << static_cast<int>(method);
        EXPECT_NEAR(cv::norm(r.rejectedR * r.rejectedR.t(), Mat::eye(3, 3, CV_64F)), 0.0, 1e-9);
        EXPECT_NEAR(cv::norm(r.rejectedT), 1.0, 1e-9) << static_cast<int>(method);
    }
}

TEST(Rcme_Rejected, a_success_reports_no_rejected_model)
{
    const SyntheticScene s = genericTestScene(3);
    const Report r = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, Params());
    ASSERT_EQ(r.status, STATUS_SUCCESS) << r.message;
    EXPECT_TRUE(r.rejectedF.empty() && r.rejectedR.empty() && r.rejectedT.empty());
}

// Without K, a plane or a pure rotation leaves F undetermined: degenerate, for every method.
TEST(Rcme_Degeneracy, planar_scenes_and_pure_rotations_without_k_are_degenerate)
{
    const Method methods[] = {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC,
                              METHOD_COV_RANSAC};
    for (Degeneracy kind : {Degeneracy::Plane, Degeneracy::PureRotation})
        for (Method method : methods)
            for (int seed = 0; seed < testRuns(4, 1); ++seed) {
                const TwoViews v = degenerateScene(kind, seed);
                Params params;
                params.method = method;
                params.randomGeneratorState = seed;
                const Report r = estimateRelativeMotion(v.points1, v.points2, noArray(), params);
                const std::string what = cv::format(
                    "%s, method %d, seed %d", kind == Degeneracy::Plane ? "plane" : "pure rotation",
                    static_cast<int>(method), seed);
                EXPECT_NE(r.status, STATUS_SUCCESS) << what;
                if (r.status == STATUS_DEGENERATE_CONFIGURATION) {
                    EXPECT_NE(r.message.find("homography"), std::string::npos) << what;
                }
                EXPECT_TRUE(r.F.empty() && r.R.empty()) << what;
                ASSERT_EQ(r.mask.rows, v.points1.rows) << what;
                EXPECT_EQ(countNonZero(r.mask), 0) << what;
            }
}

// A pure rotation without K with few true matches among outliers (60 of 100): Torr's GRIC
// often prefers F there (its band also holds outliers along its lines, and its margin over 60
// points is a draw: 24 of these 60 scenes were returned as success when only GRIC decided). A
// homography holding most of the points sends the decision to plane and parallax, which finds no
// epipole that the off-plane points agree on beyond chance.
TEST(Rcme_Degeneracy, a_pure_rotation_among_outliers_without_k_is_degenerate)
{
    for (int seed = 0; seed < 60; ++seed) {
        const SyntheticScene s = testScene(SCENE_PURE_ROTATION, seed, 0.6, 1.0, 100);
        const Report r = estimateRelativeMotion(s.points1, s.points2, noArray(), Params());
        EXPECT_EQ(r.status, STATUS_DEGENERATE_CONFIGURATION)
            << "seed " << seed << ": " << r.message;
    }
}

// With K, a plane with translation determines the motion (E, or the homography's
// decomposition), and a pure rotation determines R.
TEST(Rcme_Degeneracy, planar_scenes_with_k_give_an_accurate_motion)
{
    const Method methods[] = {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC,
                              METHOD_COV_RANSAC};
    for (Method method : methods)
        for (int seed = 0; seed < testRuns(4, 1); ++seed) {
            const TwoViews v = degenerateScene(Degeneracy::Plane, seed);
            Params params;
            params.method = method;
            params.randomGeneratorState = seed;
            const Report r = estimateRelativeMotion(v.points1, v.points2, v.K, params);
            const std::string what = cv::format("method %d, seed %d: %s", static_cast<int>(method),
                                                seed, r.message.c_str());
            EXPECT_EQ(r.status, STATUS_SUCCESS) << what;
            if (r.status != STATUS_SUCCESS)
                continue;
            const MotionError e = compareMotion(r.R, r.t, v.R, v.t);
            // Right as issue 15 and the benchmark count it (rotation <= 5 deg, translation
            // direction <= 15 deg). The refit can stop in a local minimum of the Sampson cost on
            // the plane: measured with the default Params (gcc Release, 40 seeds per method) at
            // most 4.8 deg of translation; in the clang ASan build, MLESAC seed 0 stops at
            // 1.5 deg of rotation and 13.1 deg of translation, a cost 9 sigma^2 above the
            // motion 3 deg from the truth that the same data reach from another start.
            EXPECT_LE(e.rotationDeg, 5.0) << what;
            EXPECT_LE(e.translationDeg, 15.0) << what;
            EXPECT_GT(r.inlierCount, v.points1.rows / 2 * 8 / 10) << what;
        }
}

TEST(Rcme_Degeneracy, pure_rotations_with_k_give_the_rotation_status_and_an_accurate_r)
{
    const Method methods[] = {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC,
                              METHOD_COV_RANSAC};
    for (Method method : methods)
        for (int seed = 0; seed < testRuns(4, 1); ++seed) {
            const TwoViews v = degenerateScene(Degeneracy::PureRotation, seed);
            Params params;
            params.method = method;
            params.randomGeneratorState = seed;
            const Report r = estimateRelativeMotion(v.points1, v.points2, v.K, params);
            const std::string what = cv::format("method %d, seed %d: %s", static_cast<int>(method),
                                                seed, r.message.c_str());
            ASSERT_EQ(r.status, STATUS_PURE_ROTATION) << what;
            EXPECT_EQ(statusToString(r.status), "pure rotation");
            ASSERT_EQ(r.R.size(), Size(3, 3)) << what;
            const MotionError e = compareMotion(r.R, Mat(Vec3d(1, 0, 0)), v.R, Mat(Vec3d(1, 0, 0)));
            EXPECT_LT(e.rotationDeg, 0.3) << what;
            ASSERT_EQ(r.t.size(), Size(1, 3)) << what;
            EXPECT_EQ(countNonZero(r.t), 0) << what;
            EXPECT_TRUE(r.F.empty() && r.E.empty()) << what;
            ASSERT_EQ(r.covariance.size(), Size(3, 3)) << what;
            // The rotation's own uncertainty is small and positive (sigma 1 px, f 500 px).
            for (int k = 0; k < 3; ++k) {
                EXPECT_GT(r.covariance.at<double>(k, k), 0.0) << what;
                EXPECT_LT(std::sqrt(r.covariance.at<double>(k, k)), 1e-3) << what;
            }
            EXPECT_GT(r.inlierCount, v.points1.rows / 2 * 8 / 10) << what;
            EXPECT_EQ(r.rejectedR.size(), Size(3, 3)) << what; // the motion it turned down

            Mat E, R, t, mask, covariance;
            Status status;
            const int inliers = cv::rcme::recoverPose(v.points1, v.points2, v.K, E, R, t, params,
                                                      mask, status, covariance);
            EXPECT_EQ(status, STATUS_PURE_ROTATION) << what;
            EXPECT_TRUE(E.empty()) << what;
            EXPECT_EQ(inliers, r.inlierCount) << what;
            EXPECT_EQ(countNonZero(mask), r.inlierCount) << what;
        }
}

// The generator's own plane and pure-rotation scenes (the benchmark's hard cases use them).
TEST(Rcme_Degeneracy, generated_planes_and_pure_rotations)
{
    for (int seed = 0; seed < 3; ++seed) {
        Params params;
        params.randomGeneratorState = seed;
        const SyntheticScene plane = testScene(SCENE_PLANE, seed);
        const Report r =
            estimateRelativeMotion(plane.points1, plane.points2, plane.cameraMatrix, params);
        ASSERT_EQ(r.status, STATUS_SUCCESS) << seed << ": " << r.message;
        const MotionError e = compareMotion(r.R, r.t, plane.R, plane.t);
        // A plane 12 m away seen over a 1 m baseline determines t loosely (measured 6.1-6.4 deg
        // on seeds 0-2): held to the benchmark's bound of a right motion.
        EXPECT_LT(e.rotationDeg, 1.0) << seed;
        EXPECT_LT(e.translationDeg, 15.0) << seed;
        EXPECT_EQ(estimateRelativeMotion(plane.points1, plane.points2, noArray(), params).status,
                  STATUS_DEGENERATE_CONFIGURATION)
            << seed;

        const SyntheticScene rotation = testScene(SCENE_PURE_ROTATION, seed);
        EXPECT_EQ(countNonZero(rotation.t), 0) << seed;
        const Report q = estimateRelativeMotion(rotation.points1, rotation.points2,
                                                rotation.cameraMatrix, params);
        ASSERT_EQ(q.status, STATUS_PURE_ROTATION) << seed << ": " << q.message;
        const Mat unit = Mat(Vec3d(1, 0, 0));
        EXPECT_LT(compareMotion(q.R, unit, rotation.R, unit).rotationDeg, 0.3) << seed;
        EXPECT_EQ(
            estimateRelativeMotion(rotation.points1, rotation.points2, noArray(), params).status,
            STATUS_DEGENERATE_CONFIGURATION)
            << seed;
    }
}

TEST(Rcme_Degeneracy, without_the_test_the_same_scenes_give_a_model)
{
    int successes = 0, runs = 0;
    for (Degeneracy kind : {Degeneracy::Plane, Degeneracy::PureRotation})
        for (int seed = 0; seed < testRuns(4, 1); ++seed) {
            const TwoViews v = degenerateScene(kind, seed);
            // without the ambiguity and uncertainty tests, which flag these scenes too
            Params params = Params::asPublished(METHOD_STANDARD);
            params.randomGeneratorState = seed;
            params.degeneracyTest = false;
            successes +=
                estimateRelativeMotion(v.points1, v.points2, v.K, params).status == STATUS_SUCCESS;
            ++runs;
        }
    EXPECT_GE(successes, runs - 1);
}

TEST(Rcme_Degeneracy, scenes_with_parallax_are_not_flagged)
{
    // The corridor is the hardest case: distant walls give little parallax (measured GRIC ratio
    // H/F over 100 seeds: at least 1.018; degenerate scenes: at most 0.987).
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 10; ++seed) {
            SceneParams sp;
            sp.kind = kind;
            sp.seed = seed;
            const SyntheticScene s = generateScene(sp);
            Params params;
            params.randomGeneratorState = seed;
            const Report r = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
            EXPECT_EQ(r.status, STATUS_SUCCESS)
                << "kind " << static_cast<int>(kind) << " seed " << seed << ": " << r.message;
        }
}

#ifdef RCME_STANDALONE_TESTS

// The true motion with its translation turned by offDeg about an axis across it, as an estimate
// holding every point.
cv::rcme::detail::Estimate motionOff(const SyntheticScene& scene,
                                     const cv::rcme::detail::TwoViewData& data, double offDeg)
{
    using namespace cv::rcme::detail;
    Estimate estimate;
    Motion motion;
    cv2eigen(scene.R, motion.R);
    cv2eigen(scene.t, motion.t);
    const Eigen::Vector3d axis = motion.t.cross(Eigen::Vector3d::UnitY()).normalized();
    motion.t = Eigen::AngleAxisd(offDeg * CV_PI / 180.0, axis) * motion.t;
    setMotion(data, motion, estimate.model);
    estimate.mask.assign(data.points1.size(), 1);
    return estimate;
}

// Sparse near-plane scenes (40-60 points up to `relief` off the plane) whose motion before the
// final fit is a few degrees off: at that motion a homography explains the inliers better than F,
// at the motion the final fit moves to it does not. The planar path still picks among the plane's
// motions, but two of them that fit the plane about equally are no ambiguity there: the parallax
// decides (components/motion_space.cpp; without that rule the case of 40 points, relief 0.2,
// 3 deg off, seed 1 is flagged degenerate). Internal (cv::rcme::detail), so standalone only, as
// test_components.cpp.
TEST(Rcme_Degeneracy, a_homography_that_loses_at_the_final_fit_leaves_no_ambiguity)
{
    using namespace cv::rcme::detail;
    int checked = 0;
    for (const int points : {40, 60})
        for (const double relief : {0.2, 0.3})
            for (const double offDeg : {3.0, 6.0})
                for (int seed = 0; seed < 20; ++seed) {
                    SceneParams sp = testSceneParams(SCENE_PLANE, seed, 1.0, 1.0, points);
                    sp.planeRelief = relief;
                    const SeededScene seeded = seededScene(sp);
                    const SyntheticScene& scene = seeded.scene;
                    const TwoViewData& data = seeded.data;
                    EstimatorComponents components = createEstimator(seeded.params, data);
                    const Refinement refinement(*components.scorer, components.refiner.get());
                    const Estimate estimate = motionOff(scene, data, offDeg);
                    const Model& off = estimate.model;
                    if (!compareWithHomography(data, off.F, estimate.mask)
                             .homographyExplainsInliers ||
                        compareWithRotation(data, off.F, estimate.mask).rotationExplainsInliers)
                        continue; // no plane at the motion that is off, or a rotation's case
                    Model fitted = off;
                    std::vector<uchar> inliers = estimate.mask;
                    refinement.finalFit(data, fitted, inliers);
                    if (compareWithHomography(data, fitted.F, inliers).homographyExplainsInliers)
                        continue; // the plane wins at the final fit too
                    ++checked;
                    const SearchResult search;
                    const StageContext context{data, search, *components.scorer, refinement,
                                               *components.space};
                    const StageOutcome outcome =
                        createHomographyDegeneracyTest()->run(context, estimate);
                    const std::string where = cv::format(
                        "%d points, relief %g, %g deg off, seed %d", points, relief, offDeg, seed);
                    ASSERT_TRUE(outcome.model) << where; // the planar path ran
                    EXPECT_FALSE(outcome.verdict &&
                                 outcome.verdict->status == STATUS_DEGENERATE_CONFIGURATION)
                        << where << ": " << outcome.verdict->reason;
                }
    EXPECT_GE(checked, 10);
}

#endif // RCME_STANDALONE_TESTS

} // namespace
} // namespace opencv_test
