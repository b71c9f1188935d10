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
    Eigen::Matrix<double, 9, 7> D = Eigen::Matrix<double, 9, 7>::Zero();
    for (int k = 0; k < P; ++k)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                D(3 * r + c, k) = model.directions[k](r, c);
    // The unused block of the covariance is zero, so the full 7 columns are harmless.
    M_ = D * model.covariance * D.transpose();
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
    const double modelTerm = a.dot(M_ * a) / jj;
    distanceSquared = r * r / jj;
    // The leverage-corrected variance of a sample point can round to or below zero when the model
    // fits it exactly; a floor keeps the test statistic finite.
    variance = std::max(1e-6 * sigmaSquared_, sigmaSquared_ + (leverage ? -modelTerm : modelTerm));
}

} // namespace detail
} // namespace rcme
} // namespace cv
