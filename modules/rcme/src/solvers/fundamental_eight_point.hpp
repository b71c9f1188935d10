// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_FUNDAMENTAL_EIGHT_POINT_HPP
#define OPENCV_RCME_SOLVERS_FUNDAMENTAL_EIGHT_POINT_HPP

#include <Eigen/Core>

namespace cv {
namespace rcme {
namespace detail {

/** The matrix F, unit Frobenius norm, with x2[k]^T F x1[k] = 0 for eight correspondences in
homogeneous coordinates (Hartley-normalized for a well-conditioned result): the null vector of the
8x9 linear system, from a QR decomposition of its transpose. Rank 3 in general: enforcing rank 2
or the essential constraints is the caller's choice. False when the eight equations do not
determine F (a second near-null direction: coincident, collinear or otherwise degenerate
points). */
bool fundamentalFromEightPoints(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                                Eigen::Matrix3d& F);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
