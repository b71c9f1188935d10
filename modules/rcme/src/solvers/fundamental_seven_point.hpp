// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_FUNDAMENTAL_SEVEN_POINT_HPP
#define OPENCV_RCME_SOLVERS_FUNDAMENTAL_SEVEN_POINT_HPP

#include <Eigen/Core>

namespace cv {
namespace rcme {
namespace detail {

//! The most fundamental matrices seven correspondences admit.
constexpr int kMaxSevenPointSolutions = 3;

/** The rank-2 matrices F with x2[k]^T F x1[k] = 0 for seven correspondences in homogeneous
coordinates (Hartley-normalized for a well-conditioned result; Hartley & Zisserman, sec. 11.1.2):
the 7x9 system leaves a pencil of matrices, and det F = 0 picks up to three of them, all written
to `solutions` (returns their number). 0 when the sample does not determine the pencil
(coincident, collinear or otherwise degenerate points) or every member of it is singular. Pure
math: no allocation, no RANSAC state. */
int fundamentalFromSevenPoints(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                               Eigen::Matrix3d* solutions);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
