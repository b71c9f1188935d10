// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_ESSENTIAL_FIVE_POINT_HPP
#define OPENCV_RCME_SOLVERS_ESSENTIAL_FIVE_POINT_HPP

#include <Eigen/Core>

namespace cv {
namespace rcme {
namespace detail {

//! The most essential matrices five correspondences admit.
constexpr int kMaxFivePointSolutions = 10;

/** The essential matrices E with q2[k]^T E q1[k] = 0 for five correspondences given as rays in
normalized camera coordinates (K^-1 [x; 1], any nonzero scale), by Nister's algorithm ("An
efficient solution to the five-point relative pose problem", 2004). Writes up to
kMaxFivePointSolutions of them to `solutions`, each of unit Frobenius norm (its sign arbitrary),
and returns their number: 0 for a degenerate sample (coincident or collinear points, a
rank-deficient constraint system). Pure math: no allocation, no RANSAC state. */
int essentialFromFivePoints(const Eigen::Vector3d* q1, const Eigen::Vector3d* q2,
                            Eigen::Matrix3d* solutions);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
