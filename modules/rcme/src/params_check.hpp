// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The checks of Params, defined in params.cpp beside the defaults they check.

#ifndef OPENCV_RCME_PARAMS_CHECK_HPP
#define OPENCV_RCME_PARAMS_CHECK_HPP

#include "precomp.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! Params::maxIterations' upper limit: a larger count could run for hours, the cap keeps every
//! call bounded (OpenCV's forms clamp their maxIters into [1, this]).
constexpr int kMaxIterationsLimit = 10000000;

//! Checks every field of `params`, throwing StsBadArg (or StsNotImplemented) naming it.
void validateParams(const Params& params);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_PARAMS_CHECK_HPP
