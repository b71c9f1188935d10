// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP
#define OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP

// What an estimate is, chosen once per problem by the factory: a fundamental matrix (no camera
// matrix: 7 DoF) or a camera motion (with K: 5 DoF). The loop and the post-loop components ask the
// space; none of them branches on the camera matrix (the public functions write out what the
// model holds: F, and its motion when the space made one).

#include "framework/components.hpp"

#include <opencv2/rcme/params.hpp>

namespace cv {
namespace rcme {
namespace detail {

struct RansacResult;

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

    /** Gives a model the form of the space on `inliers` (a motion: E decomposed by cheirality on
    them, again when `redecide` even if it has one); false when it has none. */
    virtual bool liftOn(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model,
                        bool redecide) const = 0;

    /** The selected model, refined as F (result.model, mask, score), becomes the estimate of the
    space, decided on all its inliers: for a motion, the essential matrix closest to F decomposed
    by cheirality and refined in motion space. False when it cannot decide the model: the result
    is then rejected (the status says why). */
    virtual bool settleSelected(const TwoViewData& data, EstimatorComponents& components,
                                RansacResult& result) const = 0;

    /** A homography H explains the inliers of a successful result as well as its F: what the
    inliers still determine (Params::degeneracyTest; the status says what they do not). */
    virtual void resolveHomography(const TwoViewData& data, EstimatorComponents& components,
                                   const Eigen::Matrix3d& H, RansacResult& result) const = 0;

    /** The last decision, after the final fit and the final tests: the recoverPose mask
    (result.inFront) and the status it leaves. */
    virtual void finish(const TwoViewData& data, RansacResult& result) const = 0;
};

std::unique_ptr<ModelSpace> createFundamentalSpace();
std::unique_ptr<ModelSpace> createMotionSpace();

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_MODEL_SPACE_HPP
