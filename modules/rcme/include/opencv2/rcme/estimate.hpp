// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_ESTIMATE_HPP
#define OPENCV_RCME_ESTIMATE_HPP

#include "opencv2/rcme/params.hpp"

namespace cv {
namespace rcme {

//! @addtogroup rcme
//! @{

/** @brief Estimates the two-view geometry and returns everything in one Report.

@param points1 N points of the first image: Nx2, 1xN or Nx1 with two channels (CV_32F or CV_64F),
or a std::vector of Point2f or Point2d. Must be finite.
@param points2 The N corresponding points of the second image, same layout rules.
@param cameraMatrix 3x3 intrinsic matrix shared by both views, or an empty array for the
uncalibrated case (then only F is estimated).
@param params Method and parameters.

Throws cv::Exception (StsBadArg, StsBadSize, StsUnmatchedSizes) naming the argument when an
input is malformed; reports a non-success status when the input is well-formed but no
trustworthy model can be found from it.
*/
CV_EXPORTS_W Report estimateRelativeMotion(InputArray points1, InputArray points2,
                                           InputArray cameraMatrix,
                                           const Params& params = Params());

/** @brief Fundamental matrix with an explicit status.

@param points1 see estimateRelativeMotion.
@param points2 see estimateRelativeMotion.
@param params method and parameters.
@param mask output Nx1 CV_8U mask, 1 for inliers; always written (all zeros on failure).
@param status outcome; the returned matrix is empty unless it is #STATUS_SUCCESS.
@return 3x3 CV_64F fundamental matrix with ||F|| = 1 such that x2^T F x1 = 0.
*/
CV_EXPORTS_W Mat findFundamentalMat(InputArray points1, InputArray points2, const Params& params,
                                    OutputArray mask, CV_OUT Status& status);

/** @brief Fundamental matrix of a calibrated pair: the hypotheses are essential matrices, so the
returned F = K^-T E K^-1 has two equal singular values. Arguments as above plus the camera
matrix (see estimateRelativeMotion). */
CV_EXPORTS_W Mat findFundamentalMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                                    const Params& params, OutputArray mask, CV_OUT Status& status);

/** @brief Drop-in for cv::findFundamentalMat (every OpenCV 4.6 form has a twin below, with
OpenCV's argument order and defaults).

@param points1 see estimateRelativeMotion; the layouts OpenCV reads in the same form: Nx2, Nx3
(homogeneous), Nx1 or 1xN with 2 or 3 channels; with a USAC_* flag (and in the UsacParams form)
2xN and 3xN single-channel too.
@param points2 as points1.
@param method an OpenCV flag as OpenCV decodes it (FM_7POINT, FM_8POINT, FM_LMEDS, FM_RANSAC and
their combinations such as FM_RANSAC | FM_8POINT, RHO, USAC_*), mapped to the rcme method of the
same intent (doc/dropin.md), or a #Method value; other values raise StsBadArg.
@param ransacReprojThreshold inlier threshold in pixels; <= 0 or not finite: 3, as OpenCV.
@param confidence in (0, 1); outside it 0.99, as OpenCV (NaN raises StsBadArg).
@param maxIters iteration cap; <= 0 runs one iteration, as OpenCV.
@param mask output CV_8U inlier mask, always written (zeros on failure), where OpenCV writes it:
into the caller's Nx1 CV_8U array, and outside USAC also into a continuous 1xN one; else a new Nx1.
@return F in OpenCV's scale (F(2,2) = 1 where it is not 0), or an empty matrix when no trustworthy F
was found (OpenCV's "nothing found"): the OpenCV forms never throw on well-formed input; the
forms with Params tell why. On fewer than 15 points that all agree with an F (within the threshold),
that F, with every point marked; on exactly 7 such points outside USAC, every 7-point solution
stacked (3k x 3), as OpenCV.
*/
CV_EXPORTS_W Mat findFundamentalMat(InputArray points1, InputArray points2, int method,
                                    double ransacReprojThreshold, double confidence, int maxIters,
                                    OutputArray mask = noArray());

/** @overload
As in calib3d, callable from Python as findFundamentalMat(points1, points2[, method
[, ransacReprojThreshold[, confidence[, mask]]]]); the overloads above are tried first. */
CV_EXPORTS_W Mat findFundamentalMat(InputArray points1, InputArray points2, int method = FM_RANSAC,
                                    double ransacReprojThreshold = 3., double confidence = 0.99,
                                    OutputArray mask = noArray());

/** @overload
The mask-first form. Not wrapped for Python, as in calib3d (it would clash with the
form above). */
CV_EXPORTS Mat findFundamentalMat(InputArray points1, InputArray points2, OutputArray mask,
                                  int method = FM_RANSAC, double ransacReprojThreshold = 3.,
                                  double confidence = 0.99);

/** @overload
With cv::UsacParams: confidence (outside (0, 1): 0.99), maxIterations (<= 0: one),
threshold (<= 0: 1.5, UsacParams' default), randomGeneratorState, isParallel, sampler (NAPSAC
samplers run uniform sampling) and score (SCORE_METHOD_MAGSAC selects #METHOD_MLESAC) are used;
the rest has no counterpart. */
CV_EXPORTS_W Mat findFundamentalMat(InputArray points1, InputArray points2, OutputArray mask,
                                    const UsacParams& params);

/** @brief Essential matrix with an explicit status.

@param points1 see estimateRelativeMotion.
@param points2 see estimateRelativeMotion.
@param cameraMatrix 3x3 intrinsic matrix shared by both views (required).
@param params method and parameters.
@param mask output Nx1 CV_8U inlier mask, always written (zeros on failure).
@param status outcome; the returned matrix is empty unless it is #STATUS_SUCCESS.
@return 3x3 CV_64F essential matrix with singular values (1, 1, 0).
*/
CV_EXPORTS_W Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                                  const Params& params, OutputArray mask, CV_OUT Status& status);

/** @brief Drop-in for cv::findEssentialMat.

@param points1 see estimateRelativeMotion; as OpenCV reads them here: Nx2, Nx1 or 1xN with two
channels, both of one layout; with a USAC_* flag any layout of findFundamentalMat's USAC forms.
@param points2 as points1.
@param cameraMatrix 3x3 intrinsic matrix shared by both views.
@param method as in findFundamentalMat's drop-in (every flag but USAC_FM_8PTS and the #Method
values runs the 5-point solver, as OpenCV).
@param prob confidence, in (0, 1) (outside it StsBadArg, as OpenCV).
@param threshold inlier threshold in pixels; <= 0 or not finite: 1, OpenCV's default.
@param maxIters iteration cap; <= 0 runs one iteration, as OpenCV.
@param mask as in findFundamentalMat's drop-in.
@return E in OpenCV's scale (unit Frobenius norm: singular values 1/sqrt(2), 1/sqrt(2), 0), or an
empty matrix on failure (never an exception on well-formed input). On fewer than 15 points that all
agree with a motion (within the threshold, in front of both cameras), its E; on exactly 5 such
points outside USAC, every 5-point solution that puts them in front, stacked (3k x 3), as OpenCV.
*/
CV_EXPORTS_W Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                                  int method = RANSAC, double prob = 0.999, double threshold = 1.0,
                                  int maxIters = 1000, OutputArray mask = noArray());

/** @overload
Without maxIters (1000), the form of OpenCV's documentation example; not wrapped. */
CV_EXPORTS Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                                int method, double prob, double threshold, OutputArray mask);

/** @overload
Camera matrix given by focal length and principal point, as in OpenCV. */
CV_EXPORTS_W Mat findEssentialMat(InputArray points1, InputArray points2, double focal = 1.0,
                                  Point2d pp = Point2d(0, 0), int method = RANSAC,
                                  double prob = 0.999, double threshold = 1.0, int maxIters = 1000,
                                  OutputArray mask = noArray());

/** @overload
Focal length and principal point, without maxIters (1000); not wrapped. */
CV_EXPORTS Mat findEssentialMat(InputArray points1, InputArray points2, double focal, Point2d pp,
                                int method, double prob, double threshold, OutputArray mask);

/** @overload
Two cameras with distortion, as OpenCV does it: both point sets are undistorted
(cv::undistortPoints) and mapped back to pixels by the mean of the two camera matrices, which is
then the camera matrix of the estimate (so the threshold stays in pixels). The points in the
layouts cv::undistortPoints takes: CV_32F or CV_64F, continuous, Nx2, 2xN, Nx1 or 1xN. */
CV_EXPORTS_W Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                                  InputArray distCoeffs1, InputArray cameraMatrix2,
                                  InputArray distCoeffs2, int method = RANSAC, double prob = 0.999,
                                  double threshold = 1.0, OutputArray mask = noArray());

/** @overload
Two cameras with distortion and cv::UsacParams (note OpenCV's argument order: both
camera matrices, then both distortion vectors); UsacParams as in findFundamentalMat. Without
distortion the points in USAC's layouts, with it in cv::undistortPoints'. */
CV_EXPORTS_W Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                                  InputArray cameraMatrix2, InputArray dist_coeff1,
                                  InputArray dist_coeff2, OutputArray mask,
                                  const UsacParams& params);

/** @brief Estimates E robustly and recovers the motion, with status and covariance.

@param points1 see estimateRelativeMotion.
@param points2 see estimateRelativeMotion.
@param cameraMatrix 3x3 intrinsic matrix shared by both views (required).
@param E output essential matrix.
@param R output 3x3 rotation.
@param t output 3x1 unit translation: x2 = R x1 + t.
@param params method and parameters.
@param mask output Nx1 CV_8U mask of the inliers that also pass cheirality (points in front of
both cameras), as cv::recoverPose leaves it.
@param status outcome; E, R, t are empty unless it is #STATUS_SUCCESS.
@param covariance optional output 5x5 covariance of the motion in its tangent space
(see Report::covariance); empty when it is not known (e.g. refinement off).
@return the number of inliers that pass cheirality, as cv::recoverPose.
*/
CV_EXPORTS_W int recoverPose(InputArray points1, InputArray points2, InputArray cameraMatrix,
                             OutputArray E, OutputArray R, OutputArray t, const Params& params,
                             OutputArray mask, CV_OUT Status& status,
                             OutputArray covariance = noArray());

/** @brief Drop-in for cv::recoverPose of two cameras with distortion: estimates E robustly
(as the two-camera findEssentialMat) and recovers the motion from it.

@param points1 see estimateRelativeMotion.
@param points2 see estimateRelativeMotion.
@param cameraMatrix1 3x3 intrinsic matrix of the first camera.
@param distCoeffs1 distortion coefficients of the first camera, as cv::undistortPoints reads them.
@param cameraMatrix2 3x3 intrinsic matrix of the second camera.
@param distCoeffs2 distortion coefficients of the second camera.
@param E output essential matrix, in OpenCV's scale (unit norm).
@param R output rotation.
@param t output unit translation.
@param method as in findEssentialMat.
@param prob as in findEssentialMat.
@param threshold as in findEssentialMat.
@param mask output Nx1 CV_8U mask of the inliers that pass cheirality (into the caller's Nx1
CV_8U array, as OpenCV).
@return that number; on failure 0 with E empty, R = identity, t = 0 and a zero mask.
*/
CV_EXPORTS_W int recoverPose(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                             InputArray distCoeffs1, InputArray cameraMatrix2,
                             InputArray distCoeffs2, OutputArray E, OutputArray R, OutputArray t,
                             int method = RANSAC, double prob = 0.999, double threshold = 1.0,
                             InputOutputArray mask = noArray());

/** @brief Drop-in for cv::recoverPose from a known essential matrix: decomposes E and keeps the
(R, t) that puts the most points in front of both cameras.

@param points1 see estimateRelativeMotion.
@param points2 see estimateRelativeMotion.
@param cameraMatrix 3x3 intrinsic matrix shared by both views.
@param R output 3x3 rotation.
@param t output 3x1 unit translation.
@param E 3x3 essential matrix. An empty (or all-zero) E, what findEssentialMat returns when it
finds nothing, gives 0 with R = identity, t = 0 and a zero mask, so that OpenCV code keeps
running on a bad frame (cv::recoverPose would throw).
@param mask input/output: on input, non-zero entries select the points to use (all when empty);
on output, the selected points that pass cheirality.
@return the number of points that pass cheirality.
*/
CV_EXPORTS_W int recoverPose(InputArray E, InputArray points1, InputArray points2,
                             InputArray cameraMatrix, OutputArray R, OutputArray t,
                             InputOutputArray mask = noArray());

/** @overload
Camera matrix given by focal length and principal point. */
CV_EXPORTS_W int recoverPose(InputArray E, InputArray points1, InputArray points2, OutputArray R,
                             OutputArray t, double focal = 1.0, Point2d pp = Point2d(0, 0),
                             InputOutputArray mask = noArray());

/** @overload
Points count only when they triangulate closer than distanceThresh (in units of the
baseline |t| = 1) in front of both cameras; triangulatedPoints receives the 4xN homogeneous
points (CV_64F, first camera frame, normalized coordinates) of the chosen decomposition, as
cv::recoverPose gives them. */
CV_EXPORTS_W int recoverPose(InputArray E, InputArray points1, InputArray points2,
                             InputArray cameraMatrix, OutputArray R, OutputArray t,
                             double distanceThresh, InputOutputArray mask = noArray(),
                             OutputArray triangulatedPoints = noArray());

/** @brief The 6x6 covariance of the relative pose (rotation, translation) from the 5x5 tangent
covariance of Report::covariance, for a pose graph (GTSAM's Pose3 convention).

The pose is T = [R | t] (x2 = R x1 + t: camera 1's coordinates into camera 2's, |t| = 1), and the
returned matrix is the covariance of xi = (omega, v), rotation first, perturbing T on the right:
T_true = T Exp(xi), to first order R_true = R exp([omega]x) and t_true = t + R v. This is the
tangent of gtsam::Pose3 (retract / localCoordinates with its default chart agree to first
order); Sophus' SE3 orders the tangent (translation, rotation): swap the two 3x3 blocks.

The scale of t is not observable from two views: along the scale direction u = (0, R^T t) (in
xi; with inverse, (0, -t)) the variance is scaleStd^2, and u is orthogonal to every other
eigenvector. With scaleStd = 0 (default) the matrix is singular along u, marking the unknown
scale; a pose graph needs a scale prior there (e.g. scaleStd from odometry, in units of the
metric baseline; multiply the translation rows and columns by the baseline to get metres).

@param R 3x3 rotation of the estimate (Report::R).
@param t 3x1 unit translation of the estimate (Report::t).
@param covariance 5x5 tangent covariance (Report::covariance).
@param scaleStd standard deviation of the translation along t (>= 0), same unit as t.
@param inverse false: the covariance of T; true: of T^-1 = [R^T | -R^T t], camera 2's pose in
camera 1's frame (the measurement of gtsam::BetweenFactor<Pose3>(x1, x2) for camera-to-world
poses), in the same right-perturbation convention: Ad_T Sigma Ad_T^T.
@return 6x6 CV_64F symmetric covariance.
*/
CV_EXPORTS_W Mat poseCovariance(InputArray R, InputArray t, InputArray covariance,
                                double scaleStd = 0, bool inverse = false);

//! @}

} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_ESTIMATE_HPP
