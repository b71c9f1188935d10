// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_TWO_VIEW_DATA_HPP
#define OPENCV_RCME_FRAMEWORK_TWO_VIEW_DATA_HPP

// Not the public headers: the geometry, the fits and the model need none of Params (see
// framework/two_view_input.hpp), and a change there then does not recompile them.
#include "geometry/core.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! The estimation problem: validated correspondences in pixels and, when calibrated, K.
struct TwoViewData
{
    std::vector<Eigen::Vector2d> points1;
    std::vector<Eigen::Vector2d> points2;
    bool calibrated = false;
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d Kinv = Eigen::Matrix3d::Identity();
    double sigma = 1.0;     //!< noise per pixel coordinate
    double threshold = 0.0; //!< inlier threshold on the Sampson distance, pixels
    /** The bound of the propagated-uncertainty tests, d^2 <= bound * v (the paper's eq. 4):
    chi2_dof^-1(1 - alpha) of Params::alpha and consistencyDof, resolved once by
    makeTwoViewData; the default is that of the default alpha 0.05 and dof 1. */
    double consistencyBound = 3.841458820694124;
    bool useEstimatedNoise = true; //!< Params::useEstimatedNoise
    // A new field is copied by copySettings (two_view_data.cpp) too.

    int size() const { return static_cast<int>(points1.size()); }
};

/** Above this many points the fits that only decide (local optimisation, refinement rounds,
the rival motions' refits) iterate on an evenly spaced subset: a million inliers determine a
model no better than twenty thousand for those decisions, and an iteration over all of them
costs ~0.15 s. The final estimate finishes on every point. No real pair of the benchmark comes
near it, so below it nothing changes. */
constexpr size_t kMaxIteratedPoints = 20000;

/** From this many points on, VERIFICATION_AUTO verifies hypotheses by SPRT before scoring: a
hypothesis scored on every point costs more than its minimal solve from about a thousand points
on, and most hypotheses are contaminated. The same bound as kMaxIteratedPoints, so the
benchmark's pairs keep the exhaustive scoring. */
constexpr int kSprtMinPoints = static_cast<int>(kMaxIteratedPoints);

//! The k of an evenly spaced subset of `count` points: 1 up to `maxPoints` (or with maxPoints 0),
//! else the smallest k that leaves at most `maxPoints`.
inline size_t subsetStride(size_t count, size_t maxPoints = kMaxIteratedPoints)
{
    return maxPoints == 0 || count <= maxPoints ? 1 : (count + maxPoints - 1) / maxPoints;
}

//! Every k-th correspondence of `data` (k the smallest that leaves at most `maxPoints`), with its
//! camera and noise: the subset on which a decision about a large problem is made.
TwoViewData evenlySpacedSubset(const TwoViewData& data, size_t maxPoints);

/** The positions of the ones of `mask`, in order, into `indices` (sized for every point first, so
that a reused buffer never allocates again). */
void maskIndices(const std::vector<uchar>& mask, std::vector<int>& indices);

/** Reads one point set as OpenCV accepts it (Nx2 1-channel, Nx1 or 1xN 2-channel; any depth;
std::vector<Point2f/2d>). Throws StsBadArg naming `argName` when the layout is
wrong, the set is empty, or a coordinate is not finite. */
std::vector<Eigen::Vector2d> readPoints(InputArray points, const char* argName);

/** Reads an intrinsic matrix; returns false when `cameraMatrix` is empty (uncalibrated). Throws
StsBadArg naming `argName` unless it is a finite, invertible 3x3 matrix (any depth) with last
row (0, 0, k), k != 0 (the matrix is divided by k), and positive focal lengths. */
bool readCameraMatrix(InputArray cameraMatrix, const char* argName, Eigen::Matrix3d& K);

//! Builds K from OpenCV's focal length / principal point form; throws naming "focal" or "pp".
Eigen::Matrix3d cameraMatrixFromFocal(double focal, Point2d pp);

//! Width and height of the points' bounding box.
Eigen::Vector2d boundingBoxSize(const std::vector<Eigen::Vector2d>& points);

//! Writes an Nx1 CV_8U mask (the only mask layout rcme produces).
void writeMask(const std::vector<uchar>& mask, OutputArray out);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_TWO_VIEW_DATA_HPP
