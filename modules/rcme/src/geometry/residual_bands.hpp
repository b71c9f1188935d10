// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_RESIDUAL_BANDS_HPP
#define OPENCV_RCME_GEOMETRY_RESIDUAL_BANDS_HPP

#include "geometry/core.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** The number of correspondences within F's band: squared Sampson distance (as
sampsonDistanceSquared) at most `thresholdSquared`. With `mask`, also writes 1 for them and 0 for
the others (mask holds points1.size() entries). The inner loop of hypothesis scoring, run on every
point of every hypothesis: it compares r^2 with thresholdSquared |J|^2 instead of dividing, has no
branch, and is compiled for AVX2 too where the compiler can pick the variant at load time. */
int countInSampsonBand(const Eigen::Matrix3d& F, const std::vector<Eigen::Vector2d>& points1,
                       const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                       uchar* mask = nullptr);

//! The same on `count` correspondences from points1[0] and points2[0] (a block of a set).
int countInSampsonBand(const Eigen::Matrix3d& F, const Eigen::Vector2d* points1,
                       const Eigen::Vector2d* points2, size_t count, double thresholdSquared,
                       uchar* mask = nullptr);

/** countInSampsonBand for a hypothesis that only matters from `needed` inliers on (early
bail-out): it stops once the points left cannot bring the count to `needed`, checking after each
block of a few dozen points, and then returns the count so far, below `needed`; otherwise the
exact count. `pointsRead` receives the number of points it read. */
int countInSampsonBandReaching(const Eigen::Matrix3d& F,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                               int needed, size_t& pointsRead);

/** MSAC's truncated cost of F on the correspondences [begin, end) of a set, added to `cost`:
the sum of min(d^2, capSquared) over their squared Sampson distances d^2 (a point at an epipole,
whose distance is infinite, adds capSquared); `inliers` is incremented by those with d^2 at most
`thresholdSquared`. Called on blocks of points by a scorer that stops once a hypothesis cannot
matter; compiled as countInSampsonBand. */
void addTruncatedSampsonCost(const Eigen::Matrix3d& F, const std::vector<Eigen::Vector2d>& points1,
                             const std::vector<Eigen::Vector2d>& points2, size_t begin, size_t end,
                             double thresholdSquared, double capSquared, int& inliers,
                             double& cost);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
