// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_HPP
#define OPENCV_RCME_HPP

/**
@defgroup rcme Robust camera motion estimation (model quality aware RANSAC)

Estimates the fundamental matrix, the essential matrix and the relative camera motion (R, t)
between two views from putative point correspondences, robustly to outliers.

The main method, RCME @cite Yeh2021RCME, is a RANSAC whose hypotheses must pass a model-sample
consistency test and an inlier-set quality test based on the differential entropy of the
propagated uncertainty; when no hypothesis passes, it reports failure
(#STATUS_POOR_QUALITY_INPUT) instead of returning a wrong motion. The baselines of the paper
(the Gold Standard RANSAC @cite Hartley2004, MLESAC @cite Torr2000MLESAC and Cov-RANSAC
@cite Raguram2009CovRANSAC) are available through the same interface.

The functions mirror cv::findFundamentalMat, cv::findEssentialMat and cv::recoverPose:
replacing `cv::` with `cv::rcme::` in existing code compiles and works. The overloads taking a
cv::rcme::Params additionally return an explicit cv::rcme::Status, and
cv::rcme::estimateRelativeMotion returns everything in one cv::rcme::Report (including the
covariance of the motion).

Conventions: R and t map points of the first camera frame to the second, x2 = R x1 + t, with
|t| = 1, exactly as cv::recoverPose. The inlier mask is always an Nx1 CV_8U matrix of 0 and 1.
*/

#include "opencv2/rcme/batch.hpp"
#include "opencv2/rcme/estimate.hpp"
#include "opencv2/rcme/params.hpp"
#include "opencv2/rcme/synthetic.hpp"

#endif // OPENCV_RCME_HPP
