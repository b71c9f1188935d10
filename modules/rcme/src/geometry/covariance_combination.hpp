// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_COVARIANCE_COMBINATION_HPP
#define OPENCV_RCME_GEOMETRY_COVARIANCE_COMBINATION_HPP

// How the reported covariance takes the residual-based (sandwich) covariance beside the
// model-based one (components/residual_covariance.cpp).

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

/* In the coordinates where the model-based covariance is the identity (C = L L^T), the sandwich's
eigenvalues that exceed 1 by more than two of their standard errors under Gaussian noise (about
sqrt(2 / count) each: a mean of `count` squared residuals) are taken, lowered by that margin; the
others stay 1. Without the margin, the larger of two noisy estimates makes a calibrated covariance
conservative (measured in doc/covariance.md). With `lowerToo`, eigenvalues below 1 by more than the
margin are taken as well, raised by it (a direction where the sandwich is zero keeps the margin).
The model-based covariance when it is not positive definite or the sandwich is not finite. */
template <int P>
Eigen::Matrix<double, P, P> sandwichBeyondItsNoise(const Eigen::Matrix<double, P, P>& modelBased,
                                                   const Eigen::Matrix<double, P, P>& sandwich,
                                                   double count, bool lowerToo)
{
    using Matrix = Eigen::Matrix<double, P, P>;
    const Eigen::LLT<Matrix> factor(modelBased);
    if (factor.info() != Eigen::Success || !sandwich.allFinite())
        return modelBased;
    const Matrix L = factor.matrixL();
    Matrix whitened = factor.matrixL().solve(sandwich);
    whitened = factor.matrixL().solve(whitened.transpose()).transpose();
    const Eigen::SelfAdjointEigenSolver<Matrix> eig(0.5 * (whitened + whitened.transpose()));
    const double margin = 2.0 * std::sqrt(2.0 / count);
    Eigen::Matrix<double, P, 1> scales = Eigen::Matrix<double, P, 1>::Ones();
    for (int k = 0; k < P; ++k) {
        const double value = eig.eigenvalues()[k];
        if (value > 1.0 + margin)
            scales[k] = value - margin;
        else if (lowerToo && value < 1.0 - margin)
            scales[k] = std::max(value, 0.0) + margin;
    }
    const Matrix taken = eig.eigenvectors() * scales.asDiagonal() * eig.eigenvectors().transpose();
    return L * taken * L.transpose();
}

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_GEOMETRY_COVARIANCE_COMBINATION_HPP
