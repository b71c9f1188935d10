// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_ESTIMATION_PIPELINE_HPP
#define OPENCV_RCME_FRAMEWORK_ESTIMATION_PIPELINE_HPP

#include "framework/ransac_loop.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! One whole estimation: what the loop found and the estimate the stages after it left.
struct Estimation
{
    SearchResult search;
    Estimate estimate;
};

/** The paper's Fig. 1 and what follows it: the hypothesis loop (searchHypotheses), then each of
components.stages in order on the estimate, each stage's outcome applied before the next one
runs (a stage after a failure only when it runsOnFailure). No hypothesis that is not a candidate
is ever returned: with none, the status says why. */
Estimation estimateModel(const TwoViewData& data, EstimatorComponents& components);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_ESTIMATION_PIPELINE_HPP
