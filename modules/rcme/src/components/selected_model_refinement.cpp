// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 4 of Fig. 1, model refinement: the selected model refined on its inliers until they settle
// (framework/refinement.cpp), then made the estimate of the model space (a motion, with K),
// which must still pass the method's acceptance tests.

#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "framework/refinement.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class SelectedModelRefinement final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        Fit selected = estimate.fit();
        context.refinement.refineSelected(context.data, selected);
        std::optional<Verdict> failure = context.space.settleSelected(
            context.data, context.refinement, context.scorer, selected);
        if (!failure && !selected.score.isCandidate)
            failure =
                Verdict{STATUS_POOR_QUALITY_INPUT,
                        "the motion closest to the selected hypothesis fails the acceptance tests",
                        selected.model};
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
