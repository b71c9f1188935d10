// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The rival motion decision's cost gate (components/rival_motion_decision.cpp): a rival of the
// loop is refitted only when, as the loop left it, it costs little enough more than the selected
// motion to come within Params::ambiguityMargin once refitted. Internal, so standalone only, as
// test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "components/motion_support.hpp"
#include "framework/estimation_pipeline.hpp"
#include "framework/estimator_factory.hpp"
#include "test_internal_helpers.hpp"

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

// Every rival the gate leaves unrefitted (Estimate::unweighedRivals) ends, once refitted on its
// own points, more than the margin above the returned motion: the gate never hides an ambiguity
// or a cheaper motion. And it does leave rivals out (what it is for: the refits are most of the
// decision's time on real pairs).
TEST(Rcme_RivalMotionDecision, leaves_out_only_rivals_that_stay_far_once_refitted)
{
    struct Case
    {
        SceneKind kind;
        int points;
        double inlierRatio;
        bool forward;
    };
    const Case cases[] = {{SCENE_CORRIDOR, 500, 0.3, false}, {SCENE_CORRIDOR, 500, 0.8, false},
                          {SCENE_GENERIC, 40, 0.8, false},   {SCENE_GENERIC, 400, 0.2, false},
                          {SCENE_GENERIC, 200, 0.6, true},   {SCENE_PLANE, 200, 0.6, false}};
    int skipped = 0, weighedRuns = 0;
    for (const Case& c : cases)
        for (int seed = 0; seed < testRuns(6, 2); ++seed) {
            SceneParams sp = testSceneParams(c.kind, seed, c.inlierRatio, 1.0, c.points);
            sp.forwardMotion = c.forward;
            const SeededScene seeded = seededScene(sp);
            const TwoViewData& data = seeded.data;
            const Params& params = seeded.params;
            EstimatorComponents components = createEstimator(params, data);
            const Estimation result = estimateModel(data, components);
            const Estimate& estimate = result.estimate;
            if (!estimate.model.motion() || estimate.weighedMotions.empty())
                continue; // the decision did not run (no motion, or a planar scene's motion)
            ++weighedRuns;
            const double returned = truncatedCost(data, estimate.model.F);
            for (int r : estimate.unweighedRivals) {
                ++skipped;
                const std::vector<Model> refitted = refittedRivalMotions(
                    data, {result.search.rivals[static_cast<size_t>(r)]}, estimate.model, 0);
                if (refitted.empty())
                    continue; // the returned motion again once refitted
                const double gap =
                    (truncatedCost(data, refitted[0].F) - returned) / (data.sigma * data.sigma);
                EXPECT_GT(gap, params.ambiguityMargin)
                    << "scene " << c.kind << " points " << c.points << " seed " << seed;
            }
        }
    EXPECT_GT(weighedRuns, 0);
    EXPECT_GT(skipped, 0);
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
