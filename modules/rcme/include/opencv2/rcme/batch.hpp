// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_BATCH_HPP
#define OPENCV_RCME_BATCH_HPP

#include "opencv2/rcme/params.hpp"

#include <vector>

namespace cv {
namespace rcme {

//! @addtogroup rcme
//! @{

/** @brief estimateRelativeMotion on many pairs at once, spread over threads.

Each pair gives exactly the Report that estimateRelativeMotion(points1[i], points2[i],
K_i, params) gives (timeSeconds aside), whatever the thread count: pairs are independent and
each is estimated on one thread with the same Params (the same seed).

@param points1 the first image's points of every pair (layouts as in estimateRelativeMotion).
@param points2 the second image's points, one entry per entry of points1.
@param cameraMatrices empty (every pair uncalibrated), one 3x3 matrix shared by every pair, or
one entry per pair (an empty entry: that pair is uncalibrated).
@param params method and parameters of every estimation. With Params::isParallel each
estimation may also use OpenCV's threads; the result is the same.
@param threads worker threads; <= 0: cv::getNumberOfCPUs(). Never more than the pairs.
@return one Report per pair, in input order.

Throws cv::Exception naming the argument when the vectors' sizes disagree; when a pair is
malformed, every pair is still run and the exception of the first malformed pair is rethrown,
its message prefixed with "pair i: ".

Not wrapped by OpenCV's Python generator (it would need a std::vector<Report> converter); the
standalone Python module `rcme` has it as estimateRelativeMotionBatch(pairs, K, params, threads).
*/
CV_EXPORTS std::vector<Report> estimateRelativeMotionBatch(const std::vector<Mat>& points1,
                                                           const std::vector<Mat>& points2,
                                                           const std::vector<Mat>& cameraMatrices,
                                                           const Params& params = Params(),
                                                           int threads = 0);

//! @}

} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_BATCH_HPP
