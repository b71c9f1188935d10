// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_COMPONENTS_PLANE_PARALLAX_HPP
#define OPENCV_RCME_COMPONENTS_PLANE_PARALLAX_HPP

// What a homography leaves of F without a camera matrix (components/plane_parallax.cpp); used by
// the fundamental model space's answer to the degeneracy test (components/fundamental_space.cpp).

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** A homography H explains the inliers of `estimate` as well as its F (Params::degeneracyTest):
F = [e']x H is then determined by the correspondences off H's plane alone (plane and parallax).
The estimate stands, or is replaced by the plane-and-parallax F, when more of them agree with
one epipole than chance alignments explain; otherwise STATUS_DEGENERATE_CONFIGURATION with the
counts in the message. */
StageOutcome resolvePlaneAndParallax(const TwoViewData& data, Scorer& scorer,
                                     const Eigen::Matrix3d& H, const Estimate& estimate);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_COMPONENTS_PLANE_PARALLAX_HPP
