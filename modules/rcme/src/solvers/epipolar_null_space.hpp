// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_EPIPOLAR_NULL_SPACE_HPP
#define OPENCV_RCME_SOLVERS_EPIPOLAR_NULL_SPACE_HPP

#include <Eigen/Core>
#include <Eigen/QR>

#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

/** The null space of the M epipolar equations x2[k]^T F x1[k] = 0 (M = 5, 7 or 8), each a row
of a Mx9 matrix A over the row-major entries of F, scaled to unit norm: the last 9 - M columns of
Q in the QR decomposition (column pivoting) of A^T, orthonormal. False when the equations are
not independent: |R(M-1, M-1)| / |R(0, 0)|, an estimate of A's smallest to largest singular
value, at most `rankTolerance` (coincident, collinear or otherwise degenerate points). A third of
the cost of the SVD of A or of the eigen decomposition of A^T A, which the solvers used before. */
template <int M>
bool epipolarNullSpace(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2, double rankTolerance,
                       Eigen::Matrix<double, 9, 9 - M>& basis)
{
    Eigen::Matrix<double, 9, M> At;
    for (int k = 0; k < M; ++k) {
        for (int r = 0; r < 3; ++r)
            At.template block<3, 1>(3 * r, k) = x2[k](r) * x1[k];
        const double norm = At.col(k).norm();
        if (!(norm > 0) || !std::isfinite(norm))
            return false;
        At.col(k) /= norm;
    }
    const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 9, M>> qr(At);
    if (!(std::abs(qr.matrixQR()(M - 1, M - 1)) > rankTolerance * std::abs(qr.matrixQR()(0, 0))))
        return false;
    // Q's last columns: the Householder reflections applied to the last unit vectors only.
    basis.setZero();
    basis.template bottomRows<9 - M>().setIdentity();
    basis.applyOnTheLeft(qr.householderQ());
    return basis.allFinite();
}

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
