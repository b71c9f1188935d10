// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Helpers of the tests that reach cv::rcme::detail (standalone build only, see
// test_components.cpp).
#ifndef OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP
#define OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP

#include "framework/components.hpp"
#include "framework/two_view_input.hpp"

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

//! A generated scene and its problem as estimateRelativeMotion makes it with the default Params,
//! seeded with the scene's seed.
struct SeededScene
{
    cv::rcme::SyntheticScene scene;
    cv::rcme::Params params;
    cv::rcme::detail::TwoViewData data;
};
inline SeededScene seededScene(const cv::rcme::SceneParams& sceneParams)
{
    SeededScene seeded;
    seeded.scene = cv::rcme::generateScene(sceneParams);
    seeded.params.randomGeneratorState = sceneParams.seed;
    seeded.data = cv::rcme::detail::makeTwoViewData(seeded.scene.points1, seeded.scene.points2,
                                                    seeded.scene.cameraMatrix, seeded.params);
    return seeded;
}

} // namespace opencv_test

#endif // OPENCV_RCME_TEST_INTERNAL_HELPERS_HPP
