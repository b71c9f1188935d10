// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SYNTHETIC_HPP
#define OPENCV_RCME_SYNTHETIC_HPP

#include <opencv2/core.hpp>

namespace cv {
namespace rcme {

//! @addtogroup rcme
//! @{

//! Kind of synthetic two-view scene.
enum SceneKind
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    /** the paper's corridor (Sec. V-B): five walls (left, right, floor, ceiling, far end), two
    free-flying cameras inside it; hard for inlier counting because the walls are planes */
    SCENE_CORRIDOR = 0,
    //! a well-conditioned scene: points spread in depth in front of both cameras, wide baseline
    SCENE_GENERIC = 1,
    /** the generic scene's cameras looking at a plane (normal (0.1, -0.2, 1) in camera 1,
    12 m away): without the camera matrix F is not determined, with it the motion is */
    SCENE_PLANE = 2,
    /** the generic scene's points seen by a camera that only rotates (3-6 deg): R is
    determined, t is not; the ground truth t, F and E are zero */
    SCENE_PURE_ROTATION = 3
};

//! Parameters of the synthetic scene generator. Lengths in metres, image sizes in pixels.
struct CV_EXPORTS_W_SIMPLE SceneParams
{
    //! Sets every field to its documented default (the paper's corridor, n = 500, w = 0.5).
    CV_WRAP SceneParams();
    CV_PROP_RW SceneKind kind;        //!< default #SCENE_CORRIDOR
    CV_PROP_RW int numPoints;         //!< correspondences in total, inliers and outliers; 500
    CV_PROP_RW double inlierRatio;    //!< fraction of true correspondences, in [0, 1]; 0.5
    CV_PROP_RW double sigma;          //!< Gaussian noise on inlier pixels, per coordinate; 1
    CV_PROP_RW int seed;              //!< the same seed gives the same scene; 0
    CV_PROP_RW double focalLength;    //!< pixels; 500
    CV_PROP_RW int imageWidth;        //!< 640
    CV_PROP_RW int imageHeight;       //!< 480
    CV_PROP_RW double baseline;       //!< distance between the camera centres; 1
    CV_PROP_RW double corridorDepth;  //!< length of the corridor; 50
    CV_PROP_RW double corridorWidth;  //!< distance between the left and right walls; 4
    CV_PROP_RW double corridorHeight; //!< distance between the floor and the ceiling; 3
    /** the inliers are the scene points seen in the top-left inlierRegion x inlierRegion part of
    image 1 (0.5: one quadrant), the outliers still fill both images; in (0, 1], default 1 (the
    whole image) */
    CV_PROP_RW double inlierRegion;
    /** #SCENE_PLANE only: each point leaves the plane along its normal by a uniform offset in
    [-planeRelief, planeRelief] metres (a near-planar scene, little parallax off the plane);
    >= 0, default 0 */
    CV_PROP_RW double planeRelief;
    /** #SCENE_GENERIC and #SCENE_PLANE: camera 2 moves along camera 1's optical axis (the epipole
    near the image centre) instead of sideways; default false */
    CV_PROP_RW bool forwardMotion;
};

//! A generated two-view scene with its ground truth.
struct CV_EXPORTS_W_SIMPLE SyntheticScene
{
    //! An empty scene (all matrices empty).
    CV_WRAP SyntheticScene();
    CV_PROP_RW Mat points1;      //!< Nx2 CV_64F pixels in the first image
    CV_PROP_RW Mat points2;      //!< Nx2 CV_64F pixels in the second image
    CV_PROP_RW Mat inlierMask;   //!< Nx1 CV_8U, 1 for a true (noisy) correspondence
    CV_PROP_RW Mat cameraMatrix; //!< 3x3 CV_64F, shared by both views
    CV_PROP_RW Mat R;            //!< 3x3 true rotation, x2 = R x1 + t
    CV_PROP_RW Mat t; //!< 3x1 true unit translation direction (zero: #SCENE_PURE_ROTATION)
    CV_PROP_RW Mat F; //!< 3x3 true fundamental matrix, ||F|| = 1 (zero: #SCENE_PURE_ROTATION)
    CV_PROP_RW Mat E; //!< 3x3 true essential matrix [t]x R (zero: #SCENE_PURE_ROTATION)
};

/** @brief Generates a scene deterministically from its parameters.

Inliers are projections of scene points visible in both images, with Gaussian noise; outliers
are independent uniform pixels in both images. Points are shuffled so that inliers and outliers
are interleaved. Throws StsBadArg naming the field when a parameter is out of range.
*/
CV_EXPORTS_W SyntheticScene generateScene(const SceneParams& params = SceneParams());

//! Differences between an estimated and a true motion (the paper's metrics and angular ones).
struct CV_EXPORTS_W_SIMPLE MotionError
{
    //! All fields NaN.
    CV_WRAP MotionError();
    CV_PROP_RW double dq;             //!< min(|q - q_gt|, |q + q_gt|) on unit quaternions
    CV_PROP_RW double dt;             //!< |t - t_gt| on unit translations
    CV_PROP_RW double rotationDeg;    //!< angle of R_gt^T R, degrees
    CV_PROP_RW double translationDeg; //!< angle between t and t_gt, degrees
};

/** @brief Compares an estimated motion with the truth. R, Rgt: 3x3 rotations; t, tgt: 3-vectors
(normalised here). Throws StsBadArg naming the argument for wrong shapes or non-finite values. */
CV_EXPORTS_W MotionError compareMotion(InputArray R, InputArray t, InputArray Rgt, InputArray tgt);

//! @}

} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_SYNTHETIC_HPP
