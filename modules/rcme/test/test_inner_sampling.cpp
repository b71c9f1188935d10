// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Local optimisation's inner sampling (EstimatorComponents::innerSampling): minimal samples drawn
// from the inliers of each new best candidate. Internal (it has no Params switch of its own), so
// standalone only, as test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "framework/estimation_pipeline.hpp"
#include "framework/estimator_factory.hpp"

#include <opencv2/core/eigen.hpp>

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

// What the loop selects (before the final tests) on `scene` with the default Params, with the
// factory's inner samples or with `innerSamples` per round instead.
Estimation runLoop(const SyntheticScene& scene, int seed, int innerSamples = -1,
                   bool exactIterations = false)
{
    Params params;
    params.randomGeneratorState = seed;
    params.exactIterations = exactIterations;
    const TwoViewData data =
        makeTwoViewData(scene.points1, scene.points2, scene.cameraMatrix, params);
    EstimatorComponents components = createEstimator(params, data);
    if (innerSamples >= 0)
        components.innerSampling.samplesPerRound = innerSamples;
    components.stages.resize(2); // selection and refinement, the factory's first stages
    return estimateModel(data, components);
}

bool loopSelectsTheTrueMotion(const SyntheticScene& scene, int seed, int innerSamples = -1)
{
    const Estimate result = runLoop(scene, seed, innerSamples).estimate;
    if (!result.model.motion() || result.model.motion()->t.isZero())
        return false;
    Mat R, t;
    eigen2cv(result.model.motion()->R, R);
    eigen2cv(Eigen::Vector3d(result.model.motion()->t), t);
    const MotionError error = compareMotion(R, t, scene.R, scene.t);
    return error.rotationDeg <= 5 && error.translationDeg <= 15; // issue 15's "right"
}

TEST(Rcme_InnerSampling, finds_the_true_motion_where_uniform_samples_are_rarely_clean)
{
    // The corridor at inlier ratio 0.3: 1000 uniform 5-point samples hold about 2.4 clean ones,
    // and most clean ones of five noisy points in a narrow view fit a wrong motion. A wrong best
    // still holds mostly true inliers, so samples drawn among them find the true motion.
    // Tuning seeds of doc/results.md (100-299; the benchmark reports on 0-49). Measured on seeds
    // 100-159 (gcc, Release): 25 of 60 right without inner samples, 40 with them.
    const int runs = testRuns(60, 3);
    int right[2] = {0, 0};
    for (int k = 0; k < runs; ++k) {
        const SyntheticScene scene = generateScene(testSceneParams(SCENE_CORRIDOR, 100 + k, 0.3));
        right[0] += loopSelectsTheTrueMotion(scene, k, 0);
        right[1] += loopSelectsTheTrueMotion(scene, k);
    }
    std::cout << "true motion selected without / with inner samples: " << right[0] << " / "
              << right[1] << " of " << runs << std::endl;
    if (kChecksStatistics) {
        EXPECT_GE(right[1], right[0] + 10);
        EXPECT_GE(right[1], 36);
    }
}

TEST(Rcme_InnerSampling, runs_only_where_the_budget_falls_short_of_the_bound)
{
    // 5-point solver, 1000 iterations, a clean sample taken to give the right motion one time in
    // ten: inlier ratio 0.8 needs about 140 samples, so no inner sample is drawn and nothing
    // changes, adaptive or not. Inlier ratios 0.5 and 0.3 need about 1470 and 19000: inner
    // samples add hypotheses, also to an adaptive loop that stopped at its own bound (about 490
    // samples at 0.5, Params::cleanSampleSuccessRate 0.3).
    for (double inlierRatio : {0.8, 0.5, 0.3}) {
        const SyntheticScene scene = generateScene(testSceneParams(SCENE_CORRIDOR, 7, inlierRatio));
        for (bool exact : {false, true}) {
            const Estimation without = runLoop(scene, 3, 0, exact);
            const Estimation with = runLoop(scene, 3, -1, exact);
            ASSERT_EQ(with.estimate.status, STATUS_SUCCESS) << with.estimate.message;
            ASSERT_EQ(without.estimate.status, STATUS_SUCCESS) << without.estimate.message;
            EXPECT_EQ(with.search.iterations, without.search.iterations);
            if (inlierRatio > 0.6) {
                EXPECT_EQ(with.search.hypotheses, without.search.hypotheses);
                EXPECT_EQ((with.estimate.model.F - without.estimate.model.F).norm(), 0.0);
                EXPECT_EQ(with.estimate.mask, without.estimate.mask);
            } else {
                EXPECT_GT(with.search.hypotheses, without.search.hypotheses)
                    << inlierRatio << " " << exact;
            }
            if (!exact && inlierRatio == 0.5)
                EXPECT_LT(with.search.iterations, 1000); // the adaptive bound stopped the loop
        }
    }
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
