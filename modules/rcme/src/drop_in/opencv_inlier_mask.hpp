// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_DROP_IN_OPENCV_INLIER_MASK_HPP
#define OPENCV_RCME_DROP_IN_OPENCV_INLIER_MASK_HPP

#include "framework/two_view_data.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! The distance by which an OpenCV 4.6 estimator marks a model's inliers.
enum class OpenCVInlierDistance
{
    /** findFundamentalMat's RANSAC and LMedS: the larger of the two point-to-epipolar-line
    distances, pixels. */
    LargerEpipolarLineDistance,
    //! USAC's F, and findEssentialMat's RANSAC and LMedS on normalized points: Sampson's.
    Sampson,
    /** USAC's E, on normalized points: the sum of the two squared point-to-epipolar-line
    distances (its square root against the threshold). */
    SymmetricEpipolarDistance
};

/** The inlier mask (Nx1 CV_8U, 0 or 1) an OpenCV estimator gives each 3x3 `model` block: the points
whose `distance` to it is within `threshold` pixels. With a camera matrix (data.calibrated) the
model is E and the distance is taken, as OpenCV's, on points normalized by fx, fy, cx, cy against
the threshold over the mean focal length (fx + fy) / 2. */
Mat opencvInlierMask(const TwoViewData& data, const Mat& model, OpenCVInlierDistance distance);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_DROP_IN_OPENCV_INLIER_MASK_HPP
