// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

bool recoverMotion(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model)
{
    CV_Assert(data.calibrated);
    const Eigen::Matrix3d E =
        model.E.isZero() ? essentialFromFundamental(model.F, data.K) : model.E;
    if (recoverMotionFromEssential(E, data.points1, data.points2, data.Kinv, &inliers, model.R,
                                   model.t) <= 0)
        return false;
    model.E = skew(model.t) * model.R;
    model.F = fundamentalFromEssential(model.E, data.Kinv);
    model.hasMotion = true;
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
