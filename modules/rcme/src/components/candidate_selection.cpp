// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 3(b) of Fig. 1, model selection: the loop's best candidate (paper eq. 8) with its inliers,
// or, when the candidate set is empty, the failure and its reason (eq. 7: poor quality input).

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "framework/ransac_loop.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* The most supported hypothesis of a run without candidates, as the method would have returned
it without its acceptance tests: refitted on its inliers and, with K, given its motion. Only a
diagnostic (Report::rejectedF...): a minimal sample's raw hypothesis would be judged far worse
than what the data support. */
Model polishRejected(const StageContext& context, Model model)
{
    constexpr int kFitIterations = 20;
    const TwoViewData& data = context.data;
    std::vector<uchar> mask;
    context.scorer.classify(data, model, mask);
    if (!context.space.liftOn(data, mask, model, /*redecide=*/false))
        return model;
    std::vector<int> inliers;
    maskIndices(mask, inliers);
    Model fitted = model;
    if (fitModelOn(data, context.space.formOf(fitted), inliers, kFitIterations, fitted))
        model = fitted;
    context.space.liftOn(data, mask, model, /*redecide=*/true);
    return model;
}

class CandidateSelection final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate&) override
    {
        const SearchResult& search = context.search;
        const CandidateSet::Candidate* best = search.candidates.best(context.scorer);
        if (best) {
            Fit selected{best->model, best->score, {}};
            context.scorer.classify(context.data, selected.model, selected.inliers);
            return StageOutcome::revised(std::move(selected));
        }
        StageOutcome failure;
        Verdict& verdict = failure.verdict.emplace();
        if (search.degenerateSamples == search.iterations) {
            verdict.status = STATUS_DEGENERATE_CONFIGURATION;
            verdict.reason = "every minimal sample was degenerate (identical or collinear points)";
        } else {
            verdict.status = STATUS_POOR_QUALITY_INPUT;
            verdict.reason = cv::format(
                "no hypothesis passed the acceptance tests in %d iterations%s", search.iterations,
                search.outOfTime ? " (Params.timeBudget ran out)" : "");
        }
        if (search.mostSupportedInliers >= 0)
            verdict.rejected = polishRejected(context, search.mostSupported);
        return failure;
    }
};

} // namespace

std::unique_ptr<EstimationStage> createCandidateSelection()
{
    return std::make_unique<CandidateSelection>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
