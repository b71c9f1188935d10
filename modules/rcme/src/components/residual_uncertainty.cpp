// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "components/residual_uncertainty.hpp"

#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

ResidualUncertainty::ResidualUncertainty(const Model& model, double sigma)
    : F_(model.F), sigmaSquared_(sigma * sigma)
{
    CV_Assert(model.uncertaintyDof > 0 && model.uncertaintyDof <= 7);
    const int P = model.uncertaintyDof;
    // Directions as rows: row k is vec(dF/dtheta_k), so that row k times a is g_k.
    Eigen::Matrix<double, 7, 9> directions = Eigen::Matrix<double, 7, 9>::Zero();
    for (int k = 0; k < P; ++k)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                directions(k, 3 * r + c) = model.directions[k](r, c);
    // Sigma = P^T L D L^T P (the unused block of the covariance is zero and gets zero pivots), so
    // a^T D Sigma D^T a = |D^1/2 L^T P directions a|^2: P products per point instead of 81.
    const Eigen::LDLT<Eigen::Matrix<double, 7, 7>> ldlt(model.covariance);
    Eigen::Matrix<double, 7, 9> permuted = ldlt.transpositionsP() * directions;
    factor_ = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt().asDiagonal() * (ldlt.matrixU() * permuted);
}

void ResidualUncertainty::evaluate(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                                   bool leverage, double& distanceSquared, double& variance) const
{
    const Eigen::Vector3d p1 = homogeneous(x1), p2 = homogeneous(x2);
    const Eigen::Vector3d Fx1 = F_ * p1, Ftx2 = F_.transpose() * p2;
    const double r = p2.dot(Fx1);
    const double jj =
        Fx1.x() * Fx1.x() + Fx1.y() * Fx1.y() + Ftx2.x() * Ftx2.x() + Ftx2.y() * Ftx2.y();
    if (!(jj > 0)) {
        distanceSquared = std::numeric_limits<double>::infinity();
        variance = sigmaSquared_;
        return;
    }
    Eigen::Matrix<double, 9, 1> a;
    a << p2.x() * p1, p2.y() * p1, p2.z() * p1;
    const double modelTerm = factor_.lazyProduct(a).squaredNorm() / jj;
    distanceSquared = r * r / jj;
    // The leverage-corrected variance of a sample point can round to or below zero when the model
    // fits it exactly; a floor keeps the test statistic finite.
    variance = std::max(1e-6 * sigmaSquared_, sigmaSquared_ + (leverage ? -modelTerm : modelTerm));
}

} // namespace detail
} // namespace rcme
} // namespace cv
