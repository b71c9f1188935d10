// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "geometry/motion_parameterization.hpp"

#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

Eigen::Matrix3d rotationExp(const Eigen::Vector3d& omega)
{
    const double angle = omega.norm();
    if (angle < 1e-12)
        return Eigen::Matrix3d::Identity() + skew(omega);
    return Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

MotionTangent::MotionTangent(const Eigen::Matrix3d& R_, const Eigen::Vector3d& t_)
    : R(R_), t(t_.normalized())
{
    // Any unit vector not parallel to t gives the complement's basis by two cross products.
    Eigen::Index axis = 0;
    t.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d b1 = t.cross(Eigen::Vector3d::Unit(axis)).normalized();
    B.col(0) = b1;
    B.col(1) = t.cross(b1);
}

void MotionTangent::apply(const Eigen::Matrix<double, kDof, 1>& theta, Eigen::Matrix3d& Rout,
                          Eigen::Vector3d& tout) const
{
    Rout = R * rotationExp(theta.head<3>());
    tout = (t + B * theta.tail<2>()).normalized();
}

void MotionTangent::essentialDerivatives(Eigen::Matrix3d dE[kDof]) const
{
    const Eigen::Matrix3d tx = skew(t);
    for (int k = 0; k < 3; ++k)
        dE[k] = tx * R * skew(Eigen::Vector3d::Unit(k));
    // d normalize(t + B beta)/d beta at 0 is B, because B is orthogonal to the unit t.
    for (int l = 0; l < 2; ++l)
        dE[3 + l] = skew(B.col(l)) * R;
}

FundamentalTangent::FundamentalTangent(const Eigen::Matrix3d& F)
{
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    U = svd.matrixU();
    V = svd.matrixV();
    // Flipping the null-space columns keeps F (its third singular value is dropped) and makes
    // U and V proper rotations, so exp() updates stay on SO(3).
    if (U.determinant() < 0)
        U.col(2) = -U.col(2);
    if (V.determinant() < 0)
        V.col(2) = -V.col(2);
    const Eigen::Vector3d sv = svd.singularValues();
    s = sv(0) > 0 ? sv(1) / sv(0) : 0.0;
}

Eigen::Matrix3d FundamentalTangent::compose() const
{
    return U * Eigen::Vector3d(1, s, 0).asDiagonal() * V.transpose();
}

Eigen::Matrix3d FundamentalTangent::apply(const Eigen::Matrix<double, kDof, 1>& theta) const
{
    const Eigen::Matrix3d Ua = U * rotationExp(theta.segment<3>(0));
    const Eigen::Matrix3d Vb = V * rotationExp(theta.segment<3>(3));
    return Ua * Eigen::Vector3d(1, s + theta(6), 0).asDiagonal() * Vb.transpose();
}

FundamentalTangent FundamentalTangent::moved(const Eigen::Matrix<double, kDof, 1>& theta) const
{
    const double movedS = s + theta(6);
    if (!(movedS >= 0.0 && movedS <= 1.0))
        return FundamentalTangent(apply(theta)); // the singular values change order or sign
    // U exp(a) and V exp(b) stay proper rotations, and diag(1, s + theta_7, 0) is ordered: an SVD
    // of apply(theta) as it stands, without computing one.
    FundamentalTangent tangent = *this;
    tangent.U = U * rotationExp(theta.segment<3>(0));
    tangent.V = V * rotationExp(theta.segment<3>(3));
    tangent.s = movedS;
    return tangent;
}

void FundamentalTangent::derivatives(Eigen::Matrix3d dF[kDof]) const
{
    const Eigen::Matrix3d D = Eigen::Vector3d(1, s, 0).asDiagonal();
    for (int k = 0; k < 3; ++k) {
        const Eigen::Matrix3d G = skew(Eigen::Vector3d::Unit(k));
        dF[k] = U * G * D * V.transpose();
        dF[3 + k] = U * D * G.transpose() * V.transpose();
    }
    dF[6] = U * Eigen::Vector3d(0, 1, 0).asDiagonal() * V.transpose();
}

Eigen::Vector3d rotationStdDeg(const Eigen::Matrix<double, 5, 5>& covariance)
{
    return covariance.diagonal().head<3>().cwiseMax(0.0).cwiseSqrt() * (180.0 / CV_PI);
}

double translationDirectionStdDeg(const Eigen::Matrix<double, 5, 5>& covariance)
{
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> direction(
        covariance.bottomRightCorner<2, 2>());
    return std::sqrt(std::max(0.0, direction.eigenvalues()(1))) * (180.0 / CV_PI);
}

} // namespace detail
} // namespace rcme
} // namespace cv
