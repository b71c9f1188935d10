// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_ESTIMATOR_FACTORY_HPP
#define OPENCV_RCME_FRAMEWORK_ESTIMATOR_FACTORY_HPP

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! The components of the method `params` selects, for this data (params already validated).
EstimatorComponents createEstimator(const Params& params, const TwoViewData& data);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_ESTIMATOR_FACTORY_HPP
