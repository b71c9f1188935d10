// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "solvers/fundamental_eight_point.hpp"

#include <Eigen/QR>

#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

bool fundamentalFromEightPoints(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                                Eigen::Matrix3d& F)
{
    // x2^T F x1 = 0 as a column of A^T times the row-major entries of F. The last column of Q in
    // A^T = Q R is orthogonal to the eight equations: the null vector. A third of the time of the
    // eigen decomposition of A^T A, and no squaring of the condition number.
    Eigen::Matrix<double, 9, 8> At;
    for (int k = 0; k < 8; ++k)
        for (int r = 0; r < 3; ++r)
            At.block<3, 1>(3 * r, k) = x2[k](r) * x1[k];
    const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 9, 8>> qr(At);
    // |R(7, 7)| / |R(0, 0)| estimates the ratio of the smallest to the largest singular value.
    if (!(std::abs(qr.matrixQR()(7, 7)) > 1e-5 * std::abs(qr.matrixQR()(0, 0))))
        return false;
    const Eigen::Matrix<double, 9, 1> f = qr.householderQ() * Eigen::Matrix<double, 9, 1>::Unit(8);
    if (!f.allFinite())
        return false;
    F << f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8);
    F /= F.norm();
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
