// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 4 of Fig. 1, model refinement: the selected model refined on its inliers until they settle
// (framework/refinement.cpp), then made the estimate of the model space (a motion, with K),
// which must still pass the method's acceptance tests; when it does not, the next distinct motion
// the loop saw that does.

#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "framework/ransac_loop.hpp"
#include "framework/refinement.hpp"

#include <algorithm>

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* The fit refined on its inliers and settled in the model space; the verdict that turns it down,
if it does (its motion fails cheirality or, settled, the acceptance tests). */
std::optional<Verdict> refineAndSettle(const StageContext& context, Fit& fit)
{
    context.refinement.refineSelected(context.data, fit);
    std::optional<Verdict> failure =
        context.space.settleSelected(context.data, context.refinement, context.scorer, fit);
    if (!failure && !fit.score.isCandidate)
        failure = Verdict{
            STATUS_POOR_QUALITY_INPUT,
            "the motion closest to the selected hypothesis fails the acceptance tests", fit.model};
    return failure;
}

class SelectedModelRefinement final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        Fit selected = estimate.fit();
        std::optional<Verdict> failure = refineAndSettle(context, selected);
        if (failure) {
            // The selection weighed the hypotheses' bands alone; cheirality came after. A wrong E
            // can hold as many points in its band as the right one (few points, a narrow view) or
            // one more (a gross outlier far off the image, whose Sampson distance to a wrong E is
            // small), and its motion then fails. The distinct motions the loop saw, each decided
            // by its own sample's cheirality, are settled in turn, best first; the first that
            // passes becomes the estimate, and the later stages judge it as any other.
            std::vector<const RivalMotions::Rival*> rivals;
            for (const RivalMotions::Rival& rival : context.search.rivals)
                if (rival.score.isCandidate && areDistinctMotions(rival.model, estimate.model))
                    rivals.push_back(&rival);
            std::stable_sort(rivals.begin(), rivals.end(), [](const auto* a, const auto* b) {
                return a->score.value < b->score.value;
            });
            for (const RivalMotions::Rival* rival : rivals) {
                Fit attempt{rival->model, rival->score, {}};
                context.scorer.classify(context.data, attempt.model, attempt.inliers);
                if (!refineAndSettle(context, attempt))
                    return StageOutcome::revised(std::move(attempt));
            }
        }
        StageOutcome outcome = StageOutcome::revised(std::move(selected));
        outcome.verdict = std::move(failure);
        return outcome;
    }
};

} // namespace

std::unique_ptr<EstimationStage> createSelectedModelRefinement()
{
    return std::make_unique<SelectedModelRefinement>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
