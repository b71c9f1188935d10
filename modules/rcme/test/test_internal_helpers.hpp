// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Helpers of the tests that reach cv::rcme::detail (standalone build only, see
// test_components.cpp).
#ifndef OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP
#define OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP

#include "framework/components.hpp"

#include <opencv2/core/eigen.hpp>

namespace opencv_test {

//! The problem of a generated scene (sigma 1 px, threshold 1.96 px), optionally its inliers only.
inline cv::rcme::detail::TwoViewData sceneData(const cv::rcme::SyntheticScene& scene,
                                               bool calibrated, bool inliersOnly = true)
{
    cv::rcme::detail::TwoViewData data;
    for (int i = 0; i < scene.points1.rows; ++i) {
        if (inliersOnly && !scene.inlierMask.at<uchar>(i))
            continue;
        data.points1.emplace_back(scene.points1.at<double>(i, 0), scene.points1.at<double>(i, 1));
        data.points2.emplace_back(scene.points2.at<double>(i, 0), scene.points2.at<double>(i, 1));
    }
    data.calibrated = calibrated;
    if (calibrated) {
        cv::cv2eigen(scene.cameraMatrix, data.K);
        data.Kinv = data.K.inverse();
    }
    data.sigma = 1.0;
    data.threshold = 1.96;
    return data;
}

} // namespace opencv_test

#endif // OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP
