// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/estimation_pipeline.hpp"

#include "framework/refinement.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The one place that writes the estimate, its mask among it. A failure keeps no inliers, except
// a pure rotation, whose inliers are the rotation's.
void apply(StageOutcome& outcome, Estimate& estimate)
{
    if (outcome.model)
        estimate.model = std::move(*outcome.model);
    if (outcome.score)
        estimate.score = *outcome.score;
    if (outcome.inliers)
        estimate.mask = std::move(*outcome.inliers);
    if (outcome.planar)
        estimate.planar = true;
    if (outcome.rivalCostGap)
        estimate.rivalCostGap = *outcome.rivalCostGap;
    if (outcome.inFront)
        estimate.inFront = std::move(*outcome.inFront);
    if (outcome.rotation)
        estimate.rotation = std::move(*outcome.rotation);
    if (outcome.weighedMotions)
        estimate.weighedMotions = std::move(*outcome.weighedMotions);
    if (outcome.unweighedRivals)
        estimate.unweighedRivals = std::move(*outcome.unweighedRivals);
    if (!outcome.verdict)
        return;
    Verdict& verdict = *outcome.verdict;
    estimate.status = verdict.status;
    estimate.message = std::move(verdict.reason);
    if (verdict.rejected) {
        estimate.rejected = std::move(*verdict.rejected);
        estimate.hasRejected = true;
    }
    if (estimate.status != STATUS_SUCCESS && estimate.status != STATUS_PURE_ROTATION)
        std::fill(estimate.mask.begin(), estimate.mask.end(), 0);
}

} // namespace

Estimation estimateModel(const TwoViewData& data, EstimatorComponents& c)
{
    Estimation result;
    Estimate& estimate = result.estimate;
    const int n = data.size();
    estimate.mask.assign(static_cast<size_t>(n), 0);
    const int m = c.solver->sampleSize();
    if (n < m) {
        estimate.status = STATUS_NOT_ENOUGH_POINTS;
        estimate.message = cv::format("%d correspondences, the minimal solver needs %d", n, m);
    } else {
        searchHypotheses(data, c, result.search);
    }
    const Refinement refinement(*c.scorer, c.refiner.get());
    const StageContext context{data, result.search, *c.scorer, refinement, *c.space};
    for (const std::unique_ptr<EstimationStage>& stage : c.stages) {
        if (estimate.status != STATUS_SUCCESS && !stage->runsOnFailure())
            continue;
        StageOutcome outcome = stage->run(context, estimate);
        apply(outcome, estimate);
    }
    return result;
}

} // namespace detail
} // namespace rcme
} // namespace cv
