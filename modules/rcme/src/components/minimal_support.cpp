// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/components.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

double chanceOfBand(const TwoViewData& data, double threshold)
{
    const Eigen::Vector2d extent =
        boundingBoxSize(data.points2).cwiseMax(Eigen::Vector2d::Constant(threshold));
    const double band = 2.0 * std::sqrt(2.0) * threshold * extent.norm();
    return std::min(1.0, band / (extent.x() * extent.y()));
}

int minimalSupport(const TwoViewData& data, double threshold, int sampleSize, int maxIterations)
{
    const double level = 0.05 / std::max(1, maxIterations);
    return sampleSize + binomialTailBound(std::max(0, data.size() - sampleSize),
                                          chanceOfBand(data, threshold), level);
}

} // namespace detail
} // namespace rcme
} // namespace cv
