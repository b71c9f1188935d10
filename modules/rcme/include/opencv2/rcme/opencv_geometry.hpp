// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_OPENCV_GEOMETRY_HPP
#define OPENCV_RCME_OPENCV_GEOMETRY_HPP

// The OpenCV module that declares cv::findFundamentalMat, cv::findEssentialMat, cv::recoverPose,
// their method flags and cv::UsacParams: calib3d up to 4.x, 3d in 5.0, geometry from 5.1 on
// (where calib3d was split). opencv_modules.hpp, included by core.hpp, says which one this
// OpenCV has; the module's CMake links the same one.
#include <opencv2/core.hpp>

#if defined(HAVE_OPENCV_GEOMETRY)
#include <opencv2/geometry.hpp>
#elif defined(HAVE_OPENCV_3D)
#include <opencv2/3d.hpp>
#elif defined(HAVE_OPENCV_CALIB3D)
#include <opencv2/calib3d.hpp>
#else
#error "rcme needs OpenCV's calib3d (4.x), 3d (5.0) or geometry (5.1 and later) module"
#endif

#endif // OPENCV_RCME_OPENCV_GEOMETRY_HPP
