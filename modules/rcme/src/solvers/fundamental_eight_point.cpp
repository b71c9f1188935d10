// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "solvers/fundamental_eight_point.hpp"

#include "solvers/epipolar_null_space.hpp"

namespace cv {
namespace rcme {
namespace detail {

bool fundamentalFromEightPoints(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                                Eigen::Matrix3d& F)
{
    Eigen::Matrix<double, 9, 1> f;
    if (!epipolarNullSpaceByElimination<8>(x1, x2, 1e-5, f))
        return false;
    F << f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8);
    F /= F.norm();
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
