// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_EPIPOLAR_HPP
#define OPENCV_RCME_GEOMETRY_EPIPOLAR_HPP

#include "geometry/core.hpp"
#include "geometry/vector_clones.hpp"

namespace cv {
namespace rcme {
namespace detail {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v)
{
    Eigen::Matrix3d S;
    S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return S;
}

inline Eigen::Vector3d homogeneous(const Eigen::Vector2d& x)
{
    return {x.x(), x.y(), 1.0};
}

/** Squared Sampson distance of x1 <-> x2 to the epipolar geometry F, in pixels^2: the first-order
distance (x2^T F x1)^2 / |J|^2 with J = d(x2^T F x1)/d(x1, x2). Infinite where J vanishes (a
point at an epipole), so such points are never inliers. */
inline double sampsonDistanceSquared(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1,
                                     const Eigen::Vector2d& x2)
{
    const Eigen::Vector3d Fx1 = F * homogeneous(x1);
    const Eigen::Vector3d Ftx2 = F.transpose() * homogeneous(x2);
    const double r = homogeneous(x2).dot(Fx1);
    const double jj =
        Fx1.x() * Fx1.x() + Fx1.y() * Fx1.y() + Ftx2.x() * Ftx2.x() + Ftx2.y() * Ftx2.y();
    return jj > 0 ? r * r / jj : std::numeric_limits<double>::infinity();
}

/** The gradient of the Sampson distance d = r / |J| of x1 = (a, b), x2 = (c, e) with respect to the
nine entries of F, row-major: dd/dF(m, n) = x2_m x1_n / |J| - w (f_m x1_n [m < 2] + t_n x2_m
[n < 2]), with f = F x1, t = F^T x2 (their first two entries), w = d / |J|^2 and
`inverseNorm` = 1 / |J|. A model's gradient is then one dot product of nine per parameter
(projectEntryGradient), where the derivative along each direction dF would take two matrix-vector
products and two divisions. Shared by sampsonDistanceAndGradient and the fits' block kernel
(geometry/sampson_gradients.cpp), which give the same bits. */
RCME_ALWAYS_INLINE void sampsonEntryGradient(double a, double b, double c, double e, double f0,
                                             double f1, double t0, double t1, double inverseNorm,
                                             double w, double gradient[9])
{
    const double ca = c * a, cb = c * b, ea = e * a, eb = e * b;
    gradient[0] = ca * inverseNorm - w * (f0 * a + t0 * c);
    gradient[1] = cb * inverseNorm - w * (f0 * b + t1 * c);
    gradient[2] = c * inverseNorm - w * f0;
    gradient[3] = ea * inverseNorm - w * (f1 * a + t0 * e);
    gradient[4] = eb * inverseNorm - w * (f1 * b + t1 * e);
    gradient[5] = e * inverseNorm - w * f1;
    gradient[6] = a * inverseNorm - w * t0;
    gradient[7] = b * inverseNorm - w * t1;
    gradient[8] = inverseNorm;
}

//! The derivative along a direction of F (its nine entries row-major) of what `entryGradient` is
//! the gradient of: the dot product, summed in the entries' order.
RCME_ALWAYS_INLINE double projectEntryGradient(const double direction[9],
                                               const double entryGradient[9])
{
    double sum = direction[0] * entryGradient[0];
    for (int j = 1; j < 9; ++j)
        sum += direction[j] * entryGradient[j];
    return sum;
}

/** Sampson distance d = r/|J| and its gradient with respect to P model parameters, given the
derivatives dF[k] of F along them. Returns false where J vanishes. */
template <int P>
bool sampsonDistanceAndGradient(const Eigen::Matrix3d& F, const Eigen::Matrix3d* dF,
                                const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                                double& distance, Eigen::Matrix<double, 1, P>& gradient)
{
    const Eigen::Vector3d p1 = homogeneous(x1), p2 = homogeneous(x2);
    const Eigen::Vector3d Fx1 = F * p1, Ftx2 = F.transpose() * p2;
    const double r = p2.dot(Fx1);
    const double jj =
        Fx1.x() * Fx1.x() + Fx1.y() * Fx1.y() + Ftx2.x() * Ftx2.x() + Ftx2.y() * Ftx2.y();
    if (!(jj > 0))
        return false;
    const double inverseNorm = 1.0 / std::sqrt(jj);
    distance = r * inverseNorm;
    double entries[9];
    sampsonEntryGradient(x1.x(), x1.y(), x2.x(), x2.y(), Fx1.x(), Fx1.y(), Ftx2.x(), Ftx2.y(),
                         inverseNorm, distance * inverseNorm * inverseNorm, entries);
    for (int k = 0; k < P; ++k) {
        double direction[9];
        for (int m = 0; m < 3; ++m)
            for (int n = 0; n < 3; ++n)
                direction[3 * m + n] = dF[k](m, n);
        gradient[k] = projectEntryGradient(direction, entries);
    }
    return true;
}

/** Hartley's normalization of both images: the similarity T1 (T2) moving the centroid of
points1[indices] (points2[indices]) to the origin and their mean distance to sqrt(2), so that the
entries of F in normalized coordinates have comparable magnitudes. False when the points of either
image coincide. */
bool normalizingTransforms(const std::vector<Eigen::Vector2d>& points1,
                           const std::vector<Eigen::Vector2d>& points2,
                           const std::vector<int>& indices, Eigen::Matrix3d& T1,
                           Eigen::Matrix3d& T2);

//! Scales F to unit Frobenius norm with its largest-magnitude entry positive (a fixed sign).
Eigen::Matrix3d normalizeFundamental(const Eigen::Matrix3d& F);

/** The rank-2 matrix closest to F in the Frobenius norm, F - (F v) v^T with v the right singular
vector of F's smallest singular value, taken as the eigenvector of F^T F (closed-form 3x3
eigen decomposition: a fifth of the time of a 3x3 SVD, in every 8-point hypothesis). */
Eigen::Matrix3d closestRankTwo(const Eigen::Matrix3d& F);

//! Closest essential matrix: singular values replaced by (1, 1, 0).
Eigen::Matrix3d projectToEssential(const Eigen::Matrix3d& E);

//! The essential matrix closest to K^T F K: the calibrated reading of an F.
Eigen::Matrix3d essentialFromFundamental(const Eigen::Matrix3d& F, const Eigen::Matrix3d& K);

//! F = K^-T E K^-1, normalised.
Eigen::Matrix3d fundamentalFromEssential(const Eigen::Matrix3d& E, const Eigen::Matrix3d& Kinv);

/** False when no decomposition of E can put all `count` correspondences (rays q1[k] <-> q2[k] in
normalized camera coordinates) in front of both cameras. Under x2 = R x1 + t the depths obey
d2 (t x q2) = d1 (t x R q1) = d1 E q1, so the sign of (t x q2) . (E q1), t the left null vector of
E, tells for each point whether its depths agree in sign under one twisted pair of E's
decompositions or under the other: points that disagree admit no common one. A necessary
condition only, for a few flops per point and no decomposition: it lets a minimal solver drop
most of its spurious solutions before they are scored on every point. */
bool admitsCommonCheirality(const Eigen::Matrix3d& E, const Eigen::Vector3d* q1,
                            const Eigen::Vector3d* q2, int count);

/** Counts the `selection`ed points (null: all) that triangulate in front of both cameras under
x2 = R x1 + t, closer than `distanceThreshold` baselines (as cv::recoverPose, whose default is
50). `inFront` (may be null) receives 1 for those points, 0 for the others. */
int countPointsInFront(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                       const std::vector<Eigen::Vector2d>& points1,
                       const std::vector<Eigen::Vector2d>& points2, const Eigen::Matrix3d& Kinv,
                       const std::vector<uchar>* selection, std::vector<uchar>* inFront,
                       double distanceThreshold = 50.0);

/** The decomposition of E into (R, t), x2 = R x1 + t, |t| = 1, that puts the most selected points
in front of both cameras, as cv::recoverPose chooses it. Returns that number of points. */
int recoverMotionFromEssential(const Eigen::Matrix3d& E,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2,
                               const Eigen::Matrix3d& Kinv, const std::vector<uchar>* selection,
                               Eigen::Matrix3d& R, Eigen::Vector3d& t,
                               double distanceThreshold = 50.0);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_GEOMETRY_EPIPOLAR_HPP
