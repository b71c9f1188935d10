// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The rival motion decision (the ambiguity test of Params::ambiguityMargin; calibrated data): the
// data hold two answers when a distinct motion the loop saw (RivalMotions), refitted on the points
// it explains itself, costs about as little as the selected one.

#include "components/motion_support.hpp"
#include "framework/component_factories.hpp"
#include "framework/ransac_loop.hpp"
#include "framework/refinement.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* The refit, about 0.3 ms a rival on a real pair, is spent only where it can close the gap. A
minimal sample's motion costs more than the motion refitted in its basin by an amount that grows
with the number of points (its error is spread over all of them): rivals that ended within
Params::ambiguityMargin of the selected motion after their refit cost at most 0.31 sigma^2 per
point more than it before (corridors, planes, near planes, forward motion: samples/
guard_reports.cpp's scenes), and on KITTI's VO pairs (doc/vo_front_end.md) those that ended within
10 sigma^2 of it or below it at most 0.50, while two thirds of the rivals refitted under a gate of 1
cost 0.6 to 1 and all of those ended 21.7 sigma^2 or more above it. So a rival is refitted when it
costs at most 0.6 sigma^2 per point more (plus the margin); the rival selection at the data's
noise weighs the others (Estimate::unweighedRivals). */
constexpr double kMaxRawCostPerPoint = 0.6;

/* Of those, a rival whose refit on an evenly spaced subset of kRivalSubsetPoints (a fifth of the
time of the refit on all the points of a real pair) already costs more than kScreenGapPerPoint
sigma^2 per point above the selected motion on all the points is weighed as that refit: on KITTI's
VO pairs (doc/vo_front_end.md) the subset refit's cost was at most 0.18 sigma^2 per point above the
full refit's, and 75 % of the refits were of such rivals, all 225 sigma^2 or more above the
selected motion once refitted in full (a subset refit that falls back onto the selected motion
is refitted on all the points: on 4 rivals the full refit found a distinct one). At or below
kRivalSubsetPoints points the subset is all of them. */
constexpr double kScreenGapPerPoint = 0.3;

/* Each rival motion of the loop (SearchResult::rivals) with at least half the selected model's
support, distinct from it and not too costly as it stands (above) is refitted on the points it
explains itself; the motion of least truncated cost is kept (a rival can beat the selected one:
the loop scores raw minimal-sample hypotheses; it then gets its own final fit), and when a
distinct one comes within the margin of it (Estimate::rivalCostGap below the margin) the data do
not tell the two: STATUS_UNDETERMINED_MOTION, the kept motion being the one turned down. Not on a
planar scene's motion (its rivals are the homography's decompositions, weighed by the degeneracy
test). */
class RivalMotionDecision final : public EstimationStage
{
public:
    explicit RivalMotionDecision(double margin) : margin_(margin) {}

    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const TwoViewData& data = context.data;
        if (!estimate.model.motion() || estimate.planar)
            return {};
        // The cost is MSAC's, without the planar test's cheirality term: the depth sign of far
        // points flips with the noise, and counting them as outliers handed small-baseline
        // corridors to mirrored rivals. The four motions of one E share that cost, so a refitted
        // rival's decomposition is chosen again by cheirality on all the points of its band, as the
        // selected model's was: a rival whose sample's few points chose -t (forward motion, far
        // points: on KITTI every rival within the margin was the selected motion with t reversed)
        // is then the selected motion again, not an ambiguity (refittedRivalMotions). Costs on
        // every point.
        std::vector<Model> motions{estimate.model};
        const double selectedCost = truncatedCost(data, estimate.model.F);
        const double mostRawCost =
            selectedCost + data.sigma * data.sigma * (kMaxRawCostPerPoint * data.size() + margin_);
        std::vector<int> unweighed;
        const double sigmaSquared = data.sigma * data.sigma;
        const RefitScreen screen{kRivalSubsetPoints, data.threshold * data.threshold,
                                 selectedCost +
                                     sigmaSquared * (kScreenGapPerPoint * data.size() + margin_)};
        for (Model& rival : refittedRivalMotions(
                 data, context.search.rivals, estimate.model, estimate.score.inlierCount,
                 RawCostGate{data.threshold * data.threshold, mostRawCost}, screen, &unweighed))
            motions.push_back(std::move(rival));
        std::vector<double> costs{selectedCost};
        for (size_t m = 1; m < motions.size(); ++m)
            costs.push_back(truncatedCost(data, motions[m].F));
        size_t best = 0;
        for (size_t m = 1; m < motions.size(); ++m)
            if (costs[m] < costs[best])
                best = m;
        StageOutcome outcome;
        if (best != 0) {
            // A rival explains the data better than the loop's choice: it becomes the estimate,
            // with its own final fit.
            Fit chosen{motions[best], Score(), {}};
            context.scorer.classify(data, chosen.model, chosen.inliers);
            chosen.score = context.scorer.score(data, chosen.model);
            if (chosen.score.isCandidate) {
                context.refinement.finalFit(data, chosen.model, chosen.inliers);
                costs[best] = truncatedCost(data, chosen.model.F);
                outcome = StageOutcome::revised(std::move(chosen));
            } else {
                best = 0;
            }
        }
        double gap = std::numeric_limits<double>::infinity();
        for (size_t m = 0; m < motions.size(); ++m)
            if (m != best && areDistinctMotions(motions[m], motions[best]))
                gap = std::min(gap, (costs[m] - costs[best]) / (data.sigma * data.sigma));
        const double rivalCostGap = std::max(0.0, gap);
        outcome.rivalCostGap = rivalCostGap;
        outcome.weighedMotions = std::move(motions);
        outcome.unweighedRivals = std::move(unweighed);
        if (rivalCostGap < margin_)
            outcome.verdict = Verdict{
                STATUS_UNDETERMINED_MOTION,
                cv::format("a distinct motion explains the inliers about as well (cost gap %.1f "
                           "sigma^2 < Params.ambiguityMargin %.1f): the motion is not determined",
                           rivalCostGap, margin_),
                outcome.model ? *outcome.model : estimate.model};
        return outcome;
    }

private:
    double margin_;
};

} // namespace

std::unique_ptr<EstimationStage> createRivalMotionDecision(double margin)
{
    return std::make_unique<RivalMotionDecision>(margin);
}

} // namespace detail
} // namespace rcme
} // namespace cv
