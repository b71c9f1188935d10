// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_ESTIMATION_HOMOGRAPHY_SEARCH_HPP
#define OPENCV_RCME_ESTIMATION_HOMOGRAPHY_SEARCH_HPP

// Homographies of correspondences (estimation/homography_search.cpp): the four-point solution and
// the robust search of the homography test (components/homography_comparison.cpp).

#include "framework/two_view_data.hpp"

#include <vector>

namespace cv {
namespace rcme {
namespace detail {

//! Centring and scaling of a point set (Hartley's normalization).
struct Normalization
{
    Point2d centre;
    double scale = 1.0;
    //! The matrix that takes a point to its normalized coordinates.
    Eigen::Matrix3d matrix() const
    {
        Eigen::Matrix3d T;
        T << scale, 0, -scale * centre.x, 0, scale, -scale * centre.y, 0, 0, 1;
        return T;
    }
};

/** Centres `points` and scales them to a mean distance of sqrt(2) from the centre (Hartley): the
homography's linear systems are ill-conditioned in pixels. Returns what was done. */
Normalization normalizeInPlace(std::vector<Point2d>& points);

/** The homography x2 ~ H x1 of the four correspondences `sample` (h33 = 1; false when the points
do not determine one with it, e.g. three on a line). */
bool homographyOfFour(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                      const int sample[4], Eigen::Matrix3d& H);

/** held[i - begin] = whether H takes from[i] within squared distance `threshold2` of to[i] (the
transfer error in image 2, x2 against H x1 dehomogenized), for i in [begin, end); returns how many
are. Vectorized (an AVX2 clone beside the baseline, the same bits). Every homography test reads
its points through it, a block of kTransferBlock at a time where it may stop early. */
int markTransferredWithin(const Eigen::Matrix3d& H, const std::vector<Point2d>& from,
                          const std::vector<Point2d>& to, size_t begin, size_t end,
                          double threshold2, uchar* held);
constexpr size_t kTransferBlock = 32;

/** How many points of `from` H transfers within squared distance `threshold2` of `to`, counted
until that count can no longer exceed `toBeat`: the count itself when it is above `toBeat`, some
count no larger than `toBeat` otherwise (the search drops a sample that does not beat its best
either way, and stops reading its points early). */
int transferredUnlessBeaten(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                            const Eigen::Matrix3d& H, double threshold2, int toBeat);

/** The homography that holds the most of the correspondences within `transferThreshold` (the
distance of x2 from H x1 in image 2, in pixels, as cv::findHomography measures it), H(2, 2) = 1:
RANSAC over four-point samples that keep their orientation, at most 200 and until the classic
bound for confidence 0.999, then least squares (the normalized direct linear transform) on the
points it holds, taken again until they settle (at most five refits; one that holds fewer points
is not taken); a fixed seed. The homography test's quick search: a fraction of
cv::findHomography's time (no eigenproblem per sample, no final Levenberg-Marquardt fit). False
with fewer than four correspondences, sizes that differ, or no sample holding four points. */
bool dominantHomography(const std::vector<Point2d>& points1, const std::vector<Point2d>& points2,
                        double transferThreshold, Eigen::Matrix3d& H);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_ESTIMATION_HOMOGRAPHY_SEARCH_HPP
