// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The motion tests behind STATUS_UNDETERMINED_MOTION: the uncertainty bound and the ambiguity
// test (Params::maxRotationStdDeg, maxTranslationStdDeg, ambiguityMargin), each on and off.

#include "test_precomp.hpp"

#include <functional>
#include <utility>
#include <vector>

namespace opencv_test {
namespace {

SyntheticScene genericScene(int seed)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.seed = seed;
    sp.numPoints = 300;
    sp.inlierRatio = 0.7;
    return generateScene(sp);
}

TEST(Rcme_FailureSignals, uncertainty_bound_flags_only_motions_above_it)
{
    const SyntheticScene s = genericScene(1);
    cv::rcme::Params params;
    const Report free = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    ASSERT_EQ(free.status, STATUS_SUCCESS) << free.message;
    ASSERT_TRUE(std::isfinite(free.translationStdDeg));

    params.maxTranslationStdDeg = 0.5 * free.translationStdDeg;
    const Report tight = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(tight.status, STATUS_UNDETERMINED_MOTION);
    EXPECT_TRUE(tight.R.empty());
    EXPECT_FALSE(tight.rejectedR.empty()); // the motion turned down is reported
    EXPECT_EQ(countNonZero(tight.mask), 0);
    EXPECT_NE(tight.message.find("maxTranslationStdDeg"), std::string::npos) << tight.message;

    params.maxTranslationStdDeg = 2.0 * free.translationStdDeg;
    params.maxRotationStdDeg = 0.5 * cv::norm(free.rotationStdDeg, NORM_INF);
    const Report rotation = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(rotation.status, STATUS_UNDETERMINED_MOTION);
    EXPECT_NE(rotation.message.find("maxRotationStdDeg"), std::string::npos) << rotation.message;

    params.maxRotationStdDeg = 2.0 * cv::norm(free.rotationStdDeg, NORM_INF);
    const Report loose = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(loose.status, STATUS_SUCCESS) << loose.message;
}

// Below 35 inliers the final fit's covariance takes the stated sigma (the noise estimate is too
// noisy to replace it), but residuals far smaller than the stated sigma rule it out: the bound
// then reads the largest noise they allow (templeSR 11-14 at 21 inliers, doc/results.md).
TEST(Rcme_FailureSignals, uncertainty_bound_reads_the_noise_the_few_residuals_allow)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.numPoints = 25;
    sp.inlierRatio = 1.0;
    sp.sigma = 0.2; // five times below the stated 1 px
    int tested = 0;
    for (int seed = 0; seed < 3; ++seed) {
        sp.seed = seed;
        const SyntheticScene s = generateScene(sp);
        cv::rcme::Params params;
        params.maxTranslationStdDeg = 0; // the rotation's bound alone
        params.maxRotationStdDeg = 0;
        params.useEstimatedNoise = false; // Report::rotationStdDeg at the stated sigma
        const Report stated = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        ASSERT_EQ(stated.status, STATUS_SUCCESS) << stated.message;
        ASSERT_LT(countNonZero(stated.mask), 35); // the stated sigma's regime
        ++tested;
        const double atStated = cv::norm(stated.rotationStdDeg, NORM_INF);

        // Half the stated sigma's deviation: flagged when the user asks for the stated sigma...
        params.maxRotationStdDeg = 0.5 * atStated;
        const Report kept = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_EQ(kept.status, STATUS_UNDETERMINED_MOTION) << kept.message;
        // ... and returned when the residuals (0.2 px) rule 1 px out.
        params.useEstimatedNoise = true;
        const Report allowed = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_EQ(allowed.status, STATUS_SUCCESS) << "seed " << seed << ": " << allowed.message;
        // A bound below what even the largest allowed noise gives still flags.
        params.maxRotationStdDeg = 0.05 * atStated;
        const Report tight = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_EQ(tight.status, STATUS_UNDETERMINED_MOTION) << tight.message;
    }
    EXPECT_EQ(tested, 3);
}

TEST(Rcme_FailureSignals, ambiguity_test_reports_its_gap_and_flags_below_the_margin)
{
    int flagged = 0, tested = 0;
    for (int seed = 0; seed < 6; ++seed) {
        const SyntheticScene s = genericScene(seed);
        cv::rcme::Params params;
        params.solver = SOLVER_FIVE_POINT;
        params.ambiguityMargin = 0.0;
        const Report off = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_TRUE(std::isnan(off.rivalCostGap)); // off with a margin of 0
        params.ambiguityMargin = 2.0;
        const Report on = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (on.status == STATUS_SUCCESS) {
            ++tested;
            EXPECT_GE(on.rivalCostGap, 2.0); // a success has no rival within the margin
            // A well-conditioned scene keeps its right motion.
            const MotionError e = compareMotion(on.R, on.t, s.R, s.t);
            EXPECT_LT(e.rotationDeg, 2.0);
            EXPECT_LT(e.translationDeg, 5.0);
        } else if (on.status == STATUS_UNDETERMINED_MOTION) {
            ++flagged;
            EXPECT_LT(on.rivalCostGap, 2.0);
            EXPECT_FALSE(on.rejectedR.empty());
        }
        // Every finite gap is large with a margin below it: the status follows the gap.
        params.ambiguityMargin = 1e9;
        const Report all = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (std::isfinite(all.rivalCostGap)) {
            EXPECT_EQ(all.status, STATUS_UNDETERMINED_MOTION);
        }
    }
    EXPECT_GE(tested, 4) << flagged << " flagged";
}

TEST(Rcme_FailureSignals, nan_bounds_are_rejected_naming_the_field)
{
    const SyntheticScene s = genericScene(0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const char* field : {"ambiguityMargin", "maxRotationStdDeg", "maxTranslationStdDeg"}) {
        cv::rcme::Params params;
        const std::string name(field);
        (name == "ambiguityMargin"     ? params.ambiguityMargin
         : name == "maxRotationStdDeg" ? params.maxRotationStdDeg
                                       : params.maxTranslationStdDeg) = nan;
        try {
            estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
            ADD_FAILURE() << field << ": NaN accepted";
        } catch (const cv::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    }
}

// A car driving forward (KITTI): points 27-1600 m ahead, 1 m of translation along the optical
// axis, a small rotation. A rival sample's five far points can choose -t, the motion whose E is
// the selected one's up to sign and whose MSAC cost is therefore the same.
SyntheticScene forwardMotionScene(int seed)
{
    cv::RNG rng(static_cast<uint64>(seed) + 11);
    const Matx33d K(700, 0, 600, 0, 700, 180, 0, 0, 1);
    Matx33d R;
    Rodrigues(Vec3d(rng.uniform(-0.01, 0.01), rng.uniform(-0.02, 0.02), 0.0), R);
    const Vec3d t = normalize(Vec3d(rng.uniform(-0.05, 0.05), rng.uniform(-0.02, 0.02), -1.0));
    constexpr int kPoints = 1000, kInliers = 800;
    SyntheticScene s;
    projectTwoViews(
        rng, K, R, t, Size(1200, 360), 0.5, kInliers, kPoints,
        [&](const Vec3d&) { return 8.0 / rng.uniform(0.005, 0.3); }, // 27-1600 m
        s.points1, s.points2);
    s.cameraMatrix = Mat(K);
    s.R = Mat(R);
    s.t = Mat(t);
    return s;
}

TEST(Rcme_FailureSignals, forward_motion_is_not_ambiguous_with_its_mirror)
{
    int flagged = 0, wrong = 0;
    const int runs = testRuns(6, 2);
    for (int seed = 0; seed < runs; ++seed) {
        const SyntheticScene s = forwardMotionScene(seed);
        cv::rcme::Params params; // the defaults: 5-point, LO, the ambiguity test
        params.sigma = 0.5;
        params.exactIterations = true; // many rival samples, as on KITTI with N = 1000
        params.randomGeneratorState = seed;
        const Report r = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (r.status != STATUS_SUCCESS) {
            ++flagged;
            continue;
        }
        const MotionError e = compareMotion(r.R, r.t, s.R, s.t);
        wrong += e.rotationDeg > 5.0 || e.translationDeg > 15.0;
    }
    EXPECT_EQ(flagged, 0);
    EXPECT_EQ(wrong, 0);
}

// Three cases of the benchmark's hard-case suite (samples/benchmark/hard_cases.py) on which the
// defaults must not return a wrong motion as a success: points near a plane (little parallax off
// it), forward motion (the epipole in the image) and inliers in one image quadrant.
TEST(Rcme_FailureSignals, near_planar_forward_and_one_quadrant_scenes_give_right_motions)
{
    const std::vector<std::pair<const char*, std::function<void(SceneParams&)>>> cases = {
        {"near-planar",
         [](SceneParams& p) {
             p.kind = SCENE_PLANE;
             p.planeRelief = 0.5;
         }},
        {"forward motion",
         [](SceneParams& p) {
             p.kind = SCENE_GENERIC;
             p.forwardMotion = true;
         }},
        {"one quadrant",
         [](SceneParams& p) {
             p.kind = SCENE_GENERIC;
             p.inlierRegion = 0.5;
         }},
    };
    const int runs = testRuns(4, 2);
    for (const auto& scene : cases) {
        int right = 0;
        for (int seed = 0; seed < runs; ++seed) {
            SceneParams sp;
            sp.seed = seed;
            scene.second(sp);
            const SyntheticScene s = generateScene(sp);
            const Report r = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, Params());
            if (r.status != STATUS_SUCCESS)
                continue;
            const MotionError e = compareMotion(r.R, r.t, s.R, s.t);
            const bool isRight = e.rotationDeg <= 5.0 && e.translationDeg <= 15.0;
            EXPECT_TRUE(isRight) << scene.first << " seed " << seed << ": " << e.rotationDeg
                                 << " deg, " << e.translationDeg << " deg off, returned";
            right += isRight;
        }
        EXPECT_GE(right, runs - 1) << scene.first;
    }
}

TEST(Rcme_FailureSignals, statusToString_names_the_new_status)
{
    EXPECT_EQ(statusToString(STATUS_UNDETERMINED_MOTION), "undetermined motion");
}

} // namespace
} // namespace opencv_test
