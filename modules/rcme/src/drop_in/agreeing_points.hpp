// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_DROP_IN_AGREEING_POINTS_HPP
#define OPENCV_RCME_DROP_IN_AGREEING_POINTS_HPP

#include "framework/two_view_data.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** Below this many correspondences the drop-in forms answer points that all agree with a model
as OpenCV does, with that model (doc/dropin.md): the robust search cannot show support
beyond chance, nor the covariance confidence, from so few points, so a refusal there would rest
on their count alone. OpenCV's own bound: its findFundamentalMat runs RANSAC from 15 points on.
*/
constexpr int kDropInFewPoints = 15;

/** The model of few correspondences (fewer than kDropInFewPoints) that all agree with it, for the
drop-in forms once the estimate found none: every minimal subset's solutions (7-point without a
camera matrix, 5-point with one) are tried, and those that every point agrees with (Sampson
distance within the inlier threshold and, with a camera matrix, in front of both cameras) kept.

- Exactly the minimal count (7 or 5 points): all of them, stacked (3k x 3) as OpenCV stacks them
  when `stackSolutions`; otherwise only a unique one (the data cannot choose among several).
- More points: the one of least cost (sum of squared Sampson distances), refined by the Gold
  Standard fit on all the points when they all still agree with the refit; with a camera matrix
  none when another agreeing motion is distinct from it (areDistinctMotions): the points do not
  determine the motion.

Returns F (pixels, unit norm) or E (unit Frobenius norm), CV_64F; empty when no solution has every
point's agreement (a point that disagrees with each: evidence against them all). */
Mat modelOfAgreeingPoints(const TwoViewData& data, bool stackSolutions);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_DROP_IN_AGREEING_POINTS_HPP
