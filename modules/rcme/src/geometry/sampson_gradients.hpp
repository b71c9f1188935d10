// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_SAMPSON_GRADIENTS_HPP
#define OPENCV_RCME_GEOMETRY_SAMPSON_GRADIENTS_HPP

#include "geometry/core.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** The Sampson distances and their gradients of a block of at most kSampsonBlock correspondences
(coordinates one array each), with the arithmetic of sampsonDistanceAndGradient point by point:
the same values to the last bit, four points at a time on AVX2. The inner loop of every least-
squares fit (local optimisation, refinement, the final fit). `directions` holds the derivatives
dF[k] of F along the model's parameters, k < parameters, 5 or 7. On return distance[i] and
gradients[k * kSampsonBlock + i] hold point i's d and dd/dp_k, and valid[i] is 0 where J
vanishes (a point at an epipole: no distance, as sampsonDistanceAndGradient returns false; its
distance and gradients are then zeros, which add nothing to the normal equations). */
constexpr int kSampsonBlock = 64;
void sampsonGradientsOfBlock(const Eigen::Matrix3d& F, const Eigen::Matrix3d* directions,
                             int parameters, const double* x1, const double* y1, const double* x2,
                             const double* y2, int count, double* distance, double* gradients,
                             uchar* valid);

/** Squared Sampson distances of a block of at most kSampsonBlock correspondences, with the
arithmetic of sampsonDistanceSquared (the same bits; infinite where J vanishes). */
void sampsonDistancesSquaredOfBlock(const Eigen::Matrix3d& F, const double* x1, const double* y1,
                                    const double* x2, const double* y2, int count,
                                    double* distanceSquared);

/** Adds a block's terms to the Gauss-Newton system of the Sampson distances: for each point j
< count, normal[a][b] += g_a g_b (b >= a: the upper triangle of J^T J) and normal[a][P] += g_a d_j,
where g_k = gradients[k * kSampsonBlock + j], d_j = distance[j] and P = `parameters` (5 or 7);
`normal` is P rows of P + 1 (J^T J, then J^T r), row-major, and its lower triangle is left as it
is. Each entry sums the block's points in four partial sums (point j into sum j % 4) and adds
(s0 + s1) + (s2 + s3): vectorized, and the same bits on every machine. A point to leave out comes
with zeros (as sampsonGradientsOfBlock gives an invalid one). */
void accumulateNormalEquations(int parameters, const double* distance, const double* gradients,
                               int count, double* normal);

/** within[i] = 1 where sampsonDistanceSquared(F, points1[i], points2[i]) < thresholdSquared (the
same bits), 0 elsewhere; `within` is sized to the points. One vectorized pass over a whole set
(the final fit's band). */
void markWithinSampsonDistance(const Eigen::Matrix3d& F,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                               std::vector<uchar>& within);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_GEOMETRY_SAMPSON_GRADIENTS_HPP
