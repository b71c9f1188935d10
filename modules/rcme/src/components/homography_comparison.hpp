// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_COMPONENTS_HOMOGRAPHY_COMPARISON_HPP
#define OPENCV_RCME_COMPONENTS_HOMOGRAPHY_COMPARISON_HPP

// The post-loop comparison of the final inliers with a homography and a rotation
// (components/homography_comparison.cpp), and the motions of a homography; used by the
// degeneracy test there and by the motion space (components/motion_space.cpp).

#include "framework/model.hpp"

#include <limits>
#include <vector>

namespace cv {
namespace rcme {
namespace detail {

//! The squared Sampson error (pixels^2) of x2 ~ H x1; infinite where it is undefined.
double homographySampsonSquared(const Eigen::Matrix3d& H, const Eigen::Vector2d& x1,
                                const Eigen::Vector2d& x2);

//! The final inliers compared with a homography (components/homography_comparison.cpp).
struct HomographyComparison
{
    double fundamentalGric = 0.0;
    double homographyGric = 0.0;
    //! A homography explains the inliers at least as well as F: planar scene or pure rotation.
    bool homographyExplainsInliers = false;
    //! The share of the compared points (those either model explains) within H's band.
    double homographyShare = 0.0;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero(); //!< the homography (pixels), when fitted
    int comparedPoints = 0; //!< the points either model explains, over which GRIC is summed
};
/** Torr's GRIC of F and of a homography fitted (RANSAC) to the method's inliers `mask` and F's
support (the points within data.threshold of it), over the points either model explains, with
the noise of the homography's inliers (at most data.sigma); with fewer than 8 points or no
homography, nothing is flagged. `shareThatDecides`: the homography share the caller acts on
(ModelSpace::homographyShareToResolve), none by default; the quick search
(estimation/homography_search.hpp) answers alone only where its homography loses GRIC clearly and
holds a share well below it, cv::findHomography's homography decides elsewhere. */
HomographyComparison
compareWithHomography(const TwoViewData& data, const Eigen::Matrix3d& F,
                      const std::vector<uchar>& mask,
                      double shareThatDecides = std::numeric_limits<double>::infinity());

//! With K, the inliers against a rotation about the camera centre (x2 ~ K R K^-1 x1).
struct RotationComparison
{
    double rotationGric = 0.0;
    double motionGric = 0.0;
    //! The rotation explains the inliers at least as well as the motion: no translation seen.
    bool rotationExplainsInliers = false;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    //! sigma^2 (J^T J)^-1 of the rotation increment omega, R exp([omega]x), when determined.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    bool hasCovariance = false;
    std::vector<uchar> inliers; //!< the points the rotation explains (2-DoF chi-square, 95 %)
};
/** Fits a rotation to the inliers `mask` (Procrustes on the viewing rays, then Gauss-Newton on
the homography Sampson error) and compares it with the motion of F by Torr's GRIC (rotation:
manifold dimension 2, 3 parameters; motion: 3 and 5), as compareWithHomography does. Calibrated
data only. */
RotationComparison compareWithRotation(const TwoViewData& data, const Eigen::Matrix3d& F,
                                       const std::vector<uchar>& mask);
//! The motions (R, unit t) of cv::decomposeHomographyMat(H, K), as models with E and F set;
//! decompositions without translation are left out. Calibrated data only.
std::vector<Model> homographyMotions(const TwoViewData& data, const Eigen::Matrix3d& H);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_COMPONENTS_HOMOGRAPHY_COMPARISON_HPP
