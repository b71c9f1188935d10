// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_TWO_VIEW_INPUT_HPP
#define OPENCV_RCME_FRAMEWORK_TWO_VIEW_INPUT_HPP

// The problem as the public API states it (Params); apart from two_view_data.hpp so that the
// code below the API does not depend on the public headers.

#include "framework/two_view_data.hpp"
#include "params_check.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! Validates and assembles the problem; throws as readPoints/readCameraMatrix/validateParams.
TwoViewData makeTwoViewData(InputArray points1, InputArray points2, InputArray cameraMatrix,
                            const Params& params);

//! The inlier threshold in pixels: Params::threshold, or 1.96 sigma when that is <= 0.
double inlierThreshold(const Params& params);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_TWO_VIEW_INPUT_HPP
