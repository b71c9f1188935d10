// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/refinement.hpp"

namespace cv {
namespace rcme {
namespace detail {

// A refined model usually gathers inliers its minimal sample missed; a refinement the scorer does
// not keep ends the rounds, so a diverging refinement cannot spoil a good estimate.
void Refinement::refineSelected(const TwoViewData& data, Fit& fit) const
{
    constexpr int kMaxRounds = 10;
    if (!refiner_)
        return;
    for (int round = 0; round < kMaxRounds; ++round) {
        Model refined = fit.model;
        if (!refiner_->refine(data, fit.inliers, refined))
            return;
        const Score refinedScore = scorer_.score(data, refined);
        if (!scorer_.keepsRefinement(fit.score, refinedScore))
            return;
        fit.model = refined;
        fit.score = refinedScore;
        const std::vector<uchar> previousInliers = fit.inliers;
        scorer_.classify(data, fit.model, fit.inliers);
        if (fit.inliers == previousInliers)
            return;
    }
}

void Refinement::refineNewForm(const TwoViewData& data, Fit& fit) const
{
    if (refiner_)
        refiner_->refine(data, fit.inliers, fit.model);
    fit.score = scorer_.score(data, fit.model);
    scorer_.classify(data, fit.model, fit.inliers);
    refineSelected(data, fit);
}

void Refinement::finalFit(const TwoViewData& data, Model& model, std::vector<uchar>& inliers) const
{
    finalFit(data, model, inliers, FinalModel::kFitted);
}

void Refinement::finalFitUnlessWorse(const TwoViewData& data, Model& model,
                                     std::vector<uchar>& inliers) const
{
    if (!refiner_)
        return;
    Model fitted = model;
    std::vector<uchar> fittedInliers = inliers;
    finalFit(data, fitted, fittedInliers, FinalModel::kFitted);
    if (scorer_.keepsRefinement(scorer_.score(data, model), scorer_.score(data, fitted))) {
        model = std::move(fitted);
        inliers = std::move(fittedInliers);
        return;
    }
    finalFit(data, model, inliers, FinalModel::kHeld);
}

void Refinement::finalFit(const TwoViewData& data, Model& model, std::vector<uchar>& inliers,
                          FinalModel kind) const
{
    if (!refiner_)
        return;
    refiner_->finalize(data, inliers, model, kind);
    // The final fit moves the model a little: the inliers are the points it used that the
    // final model still holds.
    std::vector<uchar> held;
    scorer_.classify(data, model, held);
    for (size_t i = 0; i < held.size(); ++i)
        inliers[i] = inliers[i] && held[i];
}

} // namespace detail
} // namespace rcme
} // namespace cv
