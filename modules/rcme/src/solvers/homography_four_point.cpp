// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "solvers/homography_four_point.hpp"

#include <Eigen/LU>

#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

bool homographyFromFourPoints(const Eigen::Vector2d* x1, const Eigen::Vector2d* x2,
                              Eigen::Matrix3d& H)
{
    // u (h20 x + h21 y + 1) = h00 x + h01 y + h02, and v likewise with the second row.
    Eigen::Matrix<double, 8, 8> A;
    Eigen::Matrix<double, 8, 1> b;
    for (int k = 0; k < 4; ++k) {
        const double x = x1[k].x(), y = x1[k].y(), u = x2[k].x(), v = x2[k].y();
        A.row(2 * k) << x, y, 1, 0, 0, 0, -u * x, -u * y;
        A.row(2 * k + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
        b(2 * k) = u;
        b(2 * k + 1) = v;
    }
    Eigen::FullPivLU<Eigen::Matrix<double, 8, 8>> lu(A);
    // Relative to the largest pivot: the points' scale is about one after normalization.
    lu.setThreshold(1e-10);
    if (!lu.isInvertible())
        return false;
    const Eigen::Matrix<double, 8, 1> h = lu.solve(b);
    if (!h.allFinite())
        return false;
    H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0;
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
