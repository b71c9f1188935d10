// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "drop_in/opencv_inlier_mask.hpp"

#include "geometry/epipolar.hpp"

#include <opencv2/core/eigen.hpp>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Squared distance of x to the line l (homogeneous); infinite for a line at infinity.
double squaredLineDistance(const Eigen::Vector3d& l, const Eigen::Vector2d& x)
{
    const double norm2 = l.x() * l.x() + l.y() * l.y();
    const double r = l.dot(homogeneous(x));
    return norm2 > 0 ? r * r / norm2 : std::numeric_limits<double>::infinity();
}

double squaredDistance(OpenCVInlierDistance distance, const Eigen::Matrix3d& F,
                       const Eigen::Vector2d& x1, const Eigen::Vector2d& x2)
{
    switch (distance) {
    case OpenCVInlierDistance::LargerEpipolarLineDistance:
        return std::max(squaredLineDistance(F * homogeneous(x1), x2),
                        squaredLineDistance(F.transpose() * homogeneous(x2), x1));
    case OpenCVInlierDistance::SymmetricEpipolarDistance:
        return squaredLineDistance(F * homogeneous(x1), x2) +
               squaredLineDistance(F.transpose() * homogeneous(x2), x1);
    case OpenCVInlierDistance::Sampson:
        break;
    }
    return sampsonDistanceSquared(F, x1, x2);
}

} // namespace

Mat opencvInlierMask(const TwoViewData& data, const Mat& model, OpenCVInlierDistance distance)
{
    const int n = data.size();
    Mat mask(n, 1, CV_8U, Scalar(0));
    double threshold = data.threshold;
    // OpenCV's normalization of the points for E: (x - cx) / fx, (y - cy) / fy.
    const auto normalized = [&](const Eigen::Vector2d& x) -> Eigen::Vector2d {
        if (!data.calibrated)
            return x;
        return {(x.x() - data.K(0, 2)) / data.K(0, 0), (x.y() - data.K(1, 2)) / data.K(1, 1)};
    };
    if (data.calibrated)
        threshold /= (data.K(0, 0) + data.K(1, 1)) / 2;
    for (int r = 0; r + 3 <= model.rows; r += 3) {
        Eigen::Matrix3d F;
        cv2eigen(model.rowRange(r, r + 3), F);
        for (int i = 0; i < n; ++i) {
            const size_t k = static_cast<size_t>(i);
            if (squaredDistance(distance, F, normalized(data.points1[k]),
                                normalized(data.points2[k])) <= threshold * threshold)
                mask.at<uchar>(i) = 1;
        }
    }
    return mask;
}

} // namespace detail
} // namespace rcme
} // namespace cv
