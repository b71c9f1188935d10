// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_REFINEMENT_HPP
#define OPENCV_RCME_FRAMEWORK_REFINEMENT_HPP

// Box 4 of Fig. 1, the one place where an estimate is refined before the decisions: the rounds
// of refinement and classification of the selected model, and the final fit. The fits themselves
// are the method's Refiner; what is kept, the Scorer's. (The final polish, after the decisions,
// is a stage of its own: components/final_polish.cpp.)

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

class Refinement
{
public:
    //! `refiner` null: refinement is off (Params::refine), and every step keeps the model.
    Refinement(Scorer& scorer, Refiner* refiner) : scorer_(scorer), refiner_(refiner) {}

    /** Refines `fit` on its inliers and classifies again, until the inlier set stops changing; a
    refinement the scorer does not keep (Scorer::keepsRefinement) ends it. */
    void refineSelected(const TwoViewData& data, Fit& fit) const;

    /** The same for a model just given a new form on fit.inliers (a motion made from a refined
    F): its fit on those inliers comes first, before it is scored and classifies again (the bare
    new form can lose most of them). */
    void refineNewForm(const TwoViewData& data, Fit& fit) const;

    /** The estimate's final fit and covariance (Refiner::finalize). The inliers become the points
    of that fit that the fitted model still holds. */
    void finalFit(const TwoViewData& data, Model& model, std::vector<uchar>& inliers) const;

    /** The final fit, kept as a refinement is kept: only when the scorer does not rate it below
    the model as it came (Scorer::keepsRefinement). Otherwise the model stays where it was, with
    the inliers and covariance of a final fit held there (FinalModel::kHeld). */
    void finalFitUnlessWorse(const TwoViewData& data, Model& model,
                             std::vector<uchar>& inliers) const;

private:
    void finalFit(const TwoViewData& data, Model& model, std::vector<uchar>& inliers,
                  FinalModel kind) const;

    Scorer& scorer_;
    Refiner* refiner_;
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_REFINEMENT_HPP
