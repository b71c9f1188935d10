// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_HOMOGRAPHY_FOUR_POINT_HPP
#define OPENCV_RCME_SOLVERS_HOMOGRAPHY_FOUR_POINT_HPP

#include <Eigen/Core>

namespace cv {
namespace rcme {
namespace detail {

/** The homography H with x2[k] ~ H [x1[k]; 1] for four correspondences, with H(2, 2) = 1: the
eight linear equations of the direct linear transform solved as an 8x8 system. Meant for
coordinates centred on the points (Hartley-normalized), where H(2, 2) = 0 cannot occur for a
homography that keeps the points finite. False for a degenerate sample (three collinear points
in either image: the system is singular). */
bool homographyFromFourPoints(const Eigen::Vector2d* x1, const Eigen::Vector2d* x2,
                              Eigen::Matrix3d& H);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
