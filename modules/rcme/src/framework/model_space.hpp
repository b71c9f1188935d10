// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP
#define OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP

// What an estimate is, chosen once per problem by the factory: a fundamental matrix (no camera
// matrix: 7 DoF) or a camera motion (with K: 5 DoF). The loop and the stages after it ask the
// space; none of them branches on the camera matrix (the public functions write out what the
// model holds: F, and its motion when the space made one).

#include "framework/components.hpp"

#include <opencv2/rcme/params.hpp>

namespace cv {
namespace rcme {
namespace detail {

class ModelSpace
{
public:
    virtual ~ModelSpace() = default;

    /** Gives a minimal sample's hypothesis the form of the space, decided by the sample's points
    alone (a motion: E decomposed with the sample's cheirality, unless the solver did so); false
    when it has none. `points1`, `points2` are buffers for the sample's points. */
    virtual bool liftHypothesis(const TwoViewData& data, const std::vector<int>& sample,
                                Model& model, std::vector<Eigen::Vector2d>& points1,
                                std::vector<Eigen::Vector2d>& points2) const = 0;

    /** The form a model is refined as (estimation/model_fit.hpp): the space's own, or, for a
    model that has not been given it yet, the form it has. */
    virtual ModelForm formOf(const Model& model) const = 0;

    /** Gives a model the form of the space on `inliers` (a motion: E decomposed by cheirality on
    them, again when `redecide` even if it has one); false when it has none. */
    virtual bool liftOn(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model,
                        bool redecide) const = 0;

    /** The selected model, refined as F (`selected`: model, score, inliers), becomes the
    estimate of the space, decided on all its inliers: for a motion, the hypothesis' essential
    matrix decomposed by cheirality on the refined F's inliers and refined in motion space
    (refinement). The verdict when it cannot decide the model (the status says why); `selected`
    is then the model it turns down. */
    virtual std::optional<Verdict> settleSelected(const TwoViewData& data,
                                                  const Refinement& refinement, Scorer& scorer,
                                                  Fit& selected) const = 0;

    /** A homography H explains the inliers of a standing estimate as well as its F: what the
    inliers still determine (Params::degeneracyTest; the status says what they do not). The
    refinement gives the final fit, at which a space may check the comparison again. */
    virtual StageOutcome resolveHomography(const TwoViewData& data, const Refinement& refinement,
                                           Scorer& scorer, const Eigen::Matrix3d& H,
                                           const Estimate& estimate) const = 0;
    /** The share of the points F or H explain that H must hold for resolveHomography to decide
    even when F wins GRIC (infinity: only when H wins). */
    virtual double homographyShareToResolve() const = 0;

    /** The last decision, after the final fit and the decisions: the recoverPose mask
    (StageOutcome::inFront) and the status it leaves. */
    virtual StageOutcome finish(const TwoViewData& data, const Estimate& estimate) const = 0;
};

std::unique_ptr<ModelSpace> createFundamentalSpace();
std::unique_ptr<ModelSpace> createMotionSpace();
//! The space of the data: a motion with K, else F.
std::unique_ptr<ModelSpace> createModelSpace(const TwoViewData& data);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP
