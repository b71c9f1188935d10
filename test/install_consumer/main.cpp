// A user's program built against the installed rcme package: estimates the motion of a
// generated scene and checks it against the truth.
#include <opencv2/rcme.hpp>

#include <iostream>

int main()
{
    cv::rcme::SceneParams sceneParams;
    sceneParams.kind = cv::rcme::SCENE_GENERIC;
    sceneParams.seed = 7;
    const cv::rcme::SyntheticScene scene = cv::rcme::generateScene(sceneParams);

    cv::Mat E, R, t, mask;
    cv::rcme::Status status;
    const int inliers = cv::rcme::recoverPose(scene.points1, scene.points2, scene.cameraMatrix, E,
                                              R, t, cv::rcme::Params(), mask, status);
    if (status != cv::rcme::STATUS_SUCCESS) {
        std::cerr << "status: " << cv::rcme::statusToString(status) << "\n";
        return 1;
    }
    const cv::rcme::MotionError error = cv::rcme::compareMotion(R, t, scene.R, scene.t);
    std::cout << "inliers " << inliers << ", rotation error " << error.rotationDeg << " deg\n";
    return error.rotationDeg < 2.0 ? 0 : 1;
}
