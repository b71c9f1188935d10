// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The program of the tutorial "Relative motion of two views" (tutorials/relative_motion): SIFT
// matches of two images, the motion with cv::rcme, its status and uncertainty, then the same
// matches through the drop-in form. The tutorial includes its code from here, and the build's
// tests run it, so the two cannot drift apart.
//
//   relative_motion_tutorial image1 image2 K.txt
//
// K.txt holds the 3x3 camera matrix, row by row. Exit code 0 when rcme returns a motion, 1 when
// it reports a failure status, 2 on a usage or input error.

#include <opencv2/core.hpp>
// features2d became features in OpenCV 5 (opencv_modules.hpp, from core.hpp, says which).
#ifdef HAVE_OPENCV_FEATURES
#include <opencv2/features.hpp>
#else
#include <opencv2/features2d.hpp>
#endif
#include <opencv2/imgcodecs.hpp>
//! [include]
#include <opencv2/rcme.hpp>
//! [include]

#include <fstream>
#include <iostream>
#include <vector>

int main(int argc, char** argv)
{
    if (argc != 4) {
        std::cerr << "usage: " << argv[0] << " image1 image2 K.txt\n";
        return 2;
    }
    const cv::Mat image1 = cv::imread(argv[1], cv::IMREAD_GRAYSCALE);
    const cv::Mat image2 = cv::imread(argv[2], cv::IMREAD_GRAYSCALE);
    cv::Matx33d K;
    std::ifstream kFile(argv[3]);
    for (int i = 0; i < 9 && kFile; ++i)
        kFile >> K.val[i];
    if (image1.empty() || image2.empty() || !kFile) {
        std::cerr << "cannot read " << argv[1] << ", " << argv[2] << " or " << argv[3] << "\n";
        return 2;
    }

    //! [match]
    // Putative correspondences: SIFT, Lowe's ratio test. rcme takes them as OpenCV's estimators
    // do (here two std::vector<cv::Point2f>).
    cv::Ptr<cv::SIFT> sift = cv::SIFT::create(2000);
    std::vector<cv::KeyPoint> keypoints1, keypoints2;
    cv::Mat descriptors1, descriptors2;
    sift->detectAndCompute(image1, cv::noArray(), keypoints1, descriptors1);
    sift->detectAndCompute(image2, cv::noArray(), keypoints2, descriptors2);
    std::vector<std::vector<cv::DMatch>> knn;
    cv::BFMatcher(cv::NORM_L2).knnMatch(descriptors1, descriptors2, knn, 2);
    std::vector<cv::Point2f> points1, points2;
    for (const std::vector<cv::DMatch>& m : knn)
        if (m.size() == 2 && m[0].distance < 0.8f * m[1].distance) {
            points1.push_back(keypoints1[m[0].queryIdx].pt);
            points2.push_back(keypoints2[m[0].trainIdx].pt);
        }
    std::cout << points1.size() << " putative correspondences\n";
    //! [match]

    //! [params]
    // The defaults are the configuration with the fewest wrong motions reported as success; set
    // the noise of your matches (pixels): the inlier threshold is 1.96 sigma.
    cv::rcme::Params params;
    params.sigma = 1.0;
    params.randomGeneratorState = 7; // the same state gives the same result
    //! [params]

    //! [estimate]
    const cv::rcme::Report report = cv::rcme::estimateRelativeMotion(points1, points2, K, params);
    //! [estimate]

    //! [status]
    if (report.status != cv::rcme::STATUS_SUCCESS) {
        // No motion to trust: poor quality input, a degenerate configuration, an undetermined
        // motion or a pure rotation (then report.R holds the rotation, t is not determined).
        std::cout << "rcme: " << cv::rcme::statusToString(report.status) << ": " << report.message
                  << "\n";
        return 1;
    }
    std::cout << "rcme: " << report.inlierCount << " inliers in " << report.iterations
              << " iterations\nR = " << report.R << "\nt = " << report.t.t() << "\n";
    //! [status]

    //! [covariance]
    // The motion's uncertainty: standard deviations in degrees, and the 6x6 covariance of the
    // pose for a pose graph (GTSAM's Pose3 convention; singular along the unknown scale).
    std::cout << "rotation std (deg, about x, y, z) = " << report.rotationStdDeg.t()
              << "\ntranslation direction std (deg) = " << report.translationStdDeg
              << "\nnoise estimated from the inliers (px) = " << report.noiseSigma << "\n";
    const cv::Mat poseCov = cv::rcme::poseCovariance(report.R, report.t, report.covariance);
    std::cout << "pose covariance diagonal = " << poseCov.diag().t() << "\n";
    //! [covariance]

    //! [dropin]
    // The OpenCV forms take the same matches: change cv:: to cv::rcme::. On failure they return
    // an empty E (and recoverPose 0 inliers) instead of a wrong motion.
    cv::Mat mask, R, t;
    const cv::Mat E =
        cv::rcme::findEssentialMat(points1, points2, K, cv::RANSAC, 0.999, 1.96, 1000, mask);
    const int inliers = cv::rcme::recoverPose(E, points1, points2, K, R, t, mask);
    std::cout << "drop-in: " << inliers << " inliers in front of both cameras\n";
    //! [dropin]

    //! [compare]
    const cv::rcme::MotionError difference = cv::rcme::compareMotion(R, t, report.R, report.t);
    std::cout << "drop-in against the Report: " << difference.rotationDeg << " deg rotation, "
              << difference.translationDeg << " deg translation\n";
    //! [compare]
    return 0;
}
