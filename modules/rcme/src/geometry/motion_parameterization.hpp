// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_MOTION_PARAMETERIZATION_HPP
#define OPENCV_RCME_GEOMETRY_MOTION_PARAMETERIZATION_HPP

// Minimal local parameterizations of the epipolar geometry around an estimate, used by the
// refinement (and by the uncertainty propagation): the 5-DoF motion when K is known, the 7-DoF
// fundamental matrix otherwise. Each gives F at an increment theta and dF/dtheta at theta = 0.

#include "geometry/core.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! Rotation exp([omega]x) (Rodrigues).
Eigen::Matrix3d rotationExp(const Eigen::Vector3d& omega);

/** Motion (R, t), |t| = 1, with theta = (omega, beta): R(theta) = R exp([omega]x),
t(theta) = normalize(t + B beta), B an orthonormal basis of t's orthogonal complement. */
struct MotionTangent
{
    static constexpr int kDof = 5;
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    Eigen::Matrix<double, 3, 2> B;

    MotionTangent(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
    //! The motion at increment theta.
    void apply(const Eigen::Matrix<double, kDof, 1>& theta, Eigen::Matrix3d& Rout,
               Eigen::Vector3d& tout) const;
    //! dE/dtheta_k at theta = 0, with E = [t]x R.
    void essentialDerivatives(Eigen::Matrix3d dE[kDof]) const;
};

/** Standard deviations of a MotionTangent covariance (5x5), in degrees: of the rotation
increment about each axis, and of the translation direction along its least determined
direction (the larger semi-axis of its 1-sigma cone; beta's two coordinates are angles to first
order). */
Eigen::Vector3d rotationStdDeg(const Eigen::Matrix<double, 5, 5>& covariance);
double translationDirectionStdDeg(const Eigen::Matrix<double, 5, 5>& covariance);

/** Rank-2 F = U diag(1, s, 0) V^T with U, V rotations, theta = (a, b, c):
F(theta) = U exp([a]x) diag(1, s + c, 0) (V exp([b]x))^T. */
struct FundamentalTangent
{
    static constexpr int kDof = 7;
    Eigen::Matrix3d U, V;
    double s;

    explicit FundamentalTangent(const Eigen::Matrix3d& F);
    Eigen::Matrix3d compose() const;
    Eigen::Matrix3d apply(const Eigen::Matrix<double, kDof, 1>& theta) const;
    /** The tangent at apply(theta), whose compose() is apply(theta) normalized: from the rotated
    U, V and the moved s where that is already an SVD (0 <= s + theta_7 <= 1), else from the SVD
    of apply(theta). */
    FundamentalTangent moved(const Eigen::Matrix<double, kDof, 1>& theta) const;
    //! dF/dtheta_k at theta = 0.
    void derivatives(Eigen::Matrix3d dF[kDof]) const;
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_GEOMETRY_MOTION_PARAMETERIZATION_HPP
