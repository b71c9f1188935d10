// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The rival motion decision (the ambiguity test of Params::ambiguityMargin; calibrated data): the
// data hold two answers when a distinct motion the loop saw (RivalMotions), refitted on the points
// it explains itself, costs about as little as the selected one.

#include "components/motion_support.hpp"
#include "framework/component_factories.hpp"
#include "framework/ransac_loop.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* Each rival motion of the loop (result.rivals) with at least half the selected model's support
and distinct from it is refitted on the points it explains itself; the motion of least truncated
cost is kept (a rival can beat the selected one: the loop scores raw minimal-sample hypotheses;
it is then finalized in its turn), and when a distinct one comes within the margin of it
(result.rivalCostGap below the margin) the data do not tell the two: STATUS_UNDETERMINED_MOTION,
the kept motion being result.rejected. Not on a planar scene's motion (its rivals are the
homography's decompositions, weighed by the degeneracy test). */
class RivalMotionDecision : public EstimateTest
{
public:
    explicit RivalMotionDecision(double margin) : margin_(margin) {}

    void apply(const TwoViewData& data, EstimatorComponents& c, RansacResult& result) override
    {
        constexpr double kSupportShare = 0.5; // as RivalMotions' gate
        if (!result.model.hasMotion || result.planar)
            return;
        // The cost is MSAC's, without the planar test's cheirality term: the depth sign of far
        // points flips with the noise, and counting them as outliers handed small-baseline
        // corridors to mirrored rivals. The four motions of one E share that cost, so a refitted
        // rival's decomposition is chosen again by cheirality on all the points of its band, as the
        // selected model's was: a rival whose sample's few points chose -t (forward motion, far
        // points: on KITTI every rival within the margin was the selected motion with t reversed)
        // is then the selected motion again, not an ambiguity. A rival's refit and its
        // decomposition on a subset of a large problem; costs on every point.
        const TwoViewData subset = data.size() > static_cast<int>(kMaxIteratedPoints)
                                       ? evenlySpacedSubset(data, kMaxIteratedPoints)
                                       : TwoViewData();
        const TwoViewData& fitData = subset.points1.empty() ? data : subset;
        std::vector<Model> motions{result.model};
        std::vector<double> costs{truncatedCost(data, result.model.F)};
        std::vector<uchar> within, inFront;
        for (const RivalMotions::Rival& rival : result.rivals) {
            if (rival.score.inlierCount < kSupportShare * result.score.inlierCount ||
                !areDistinctMotions(rival.model, result.model))
                continue;
            Model refitted = rival.model;
            if (refitOnOwnPoints(fitData, refitted, within, inFront).support <= 0)
                continue;
            if (recoverMotion(fitData, within, refitted) &&
                areDistinctMotions(refitted, result.model)) {
                motions.push_back(refitted);
                costs.push_back(truncatedCost(data, refitted.F));
            }
        }
        size_t best = 0;
        for (size_t m = 1; m < motions.size(); ++m)
            if (costs[m] < costs[best])
                best = m;
        if (best != 0) {
            // A rival explains the data better than the loop's choice: it becomes the estimate.
            Model chosen = motions[best];
            std::vector<uchar> mask;
            c.scorer->classify(data, chosen, mask);
            const Score score = c.scorer->score(data, chosen);
            if (score.isCandidate) {
                result.model = chosen;
                result.mask = mask;
                result.score = score;
                finalizeModel(data, c, result);
                costs[best] = truncatedCost(data, result.model.F);
            } else {
                best = 0;
            }
        }
        double gap = std::numeric_limits<double>::infinity();
        for (size_t m = 0; m < motions.size(); ++m)
            if (m != best && areDistinctMotions(motions[m], motions[best]))
                gap = std::min(gap, (costs[m] - costs[best]) / (data.sigma * data.sigma));
        result.rivalCostGap = std::max(0.0, gap);
        if (result.rivalCostGap < margin_)
            rejectModel(result, STATUS_UNDETERMINED_MOTION,
                        cv::format("a distinct motion explains the inliers about as well (cost gap "
                                   "%.1f sigma^2 < Params.ambiguityMargin %.1f): the motion is not "
                                   "determined",
                                   result.rivalCostGap, margin_),
                        result.model);
    }

private:
    double margin_;
};

} // namespace

std::unique_ptr<EstimateTest> createRivalMotionDecision(double margin)
{
    return std::make_unique<RivalMotionDecision>(margin);
}

} // namespace detail
} // namespace rcme
} // namespace cv
