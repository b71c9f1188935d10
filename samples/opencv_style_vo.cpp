// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

/*
A monocular visual odometry written the way public OpenCV examples write it: ORB matches between
consecutive frames, then per frame

    E = findEssentialMat(cur, prev, focal, pp, RANSAC, 0.999, 1.0, mask);
    recoverPose(E, cur, prev, R, t, focal, pp, mask);

with no status check. It is built twice from this one source (samples/CMakeLists.txt): with
VO_NAMESPACE=cv (OpenCV's estimator) and with VO_NAMESPACE=cv::rcme (the drop-in), to show that
the namespace swap compiles and keeps running on frames where the car stands still
(--duplicate repeats frames, so that a pair has no motion at all).

    rcme_opencv_style_vo_{cv,rcme} <KITTI sequence folder> [--frames N] [--duplicate i,j,...]

Prints one line per pair and then "median rotation error: X deg" against the ground truth
(poses.txt); exit code 2 when the folder is missing. The rotation error uses only this file's
own code, so the two builds differ in nothing but the namespace of the two calls.
*/

#include <opencv2/core.hpp>
// OpenCV 5 split calib3d (findEssentialMat and recoverPose are in geometry from 5.1 on) and
// renamed features2d to features; opencv_modules.hpp, from core.hpp, says which modules exist.
#ifdef HAVE_OPENCV_GEOMETRY
#include <opencv2/features.hpp>
#include <opencv2/geometry.hpp>
#else
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#endif
#include <opencv2/imgcodecs.hpp>
#ifdef VO_USES_RCME
#include <opencv2/rcme.hpp>
#endif

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#ifndef VO_NAMESPACE
#define VO_NAMESPACE cv
#endif

namespace {

std::vector<std::vector<double>> readRows(const std::string& path)
{
    std::ifstream in(path);
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line.substr(line.find_first_of("-0123456789.")));
        std::vector<double> row;
        for (double v; s >> v;)
            row.push_back(v);
        if (!row.empty())
            rows.push_back(row);
    }
    return rows;
}

cv::Mat rotationOf(const std::vector<double>& pose)
{
    return cv::Mat(cv::Matx33d(pose[0], pose[1], pose[2], pose[4], pose[5], pose[6], pose[8],
                               pose[9], pose[10]));
}

double angleDeg(const cv::Mat& R)
{
    const double c = std::max(-1.0, std::min(1.0, (cv::trace(R)[0] - 1) / 2));
    return std::acos(c) * 180.0 / CV_PI;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::cerr << "usage: " << argv[0] << " <sequence folder> [--frames N] [--duplicate i,j]\n";
        return 2;
    }
    const std::string folder = argv[1];
    int frames = 12;
    std::set<int> duplicated;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        if (option == "--frames") {
            frames = std::atoi(argv[i + 1]);
        } else if (option == "--duplicate") {
            std::stringstream list(argv[i + 1]);
            for (std::string item; std::getline(list, item, ',');)
                duplicated.insert(std::atoi(item.c_str()));
        } else {
            std::cerr << "unknown option " << option << "\n";
            return 2;
        }
    }
    const auto calib = readRows(folder + "/calib.txt");
    const auto poses = readRows(folder + "/poses.txt");
    if (calib.empty() || calib[0].size() < 12 || poses.empty()) {
        std::cerr << "no KITTI sequence in " << folder << " (calib.txt, poses.txt)\n";
        return 2;
    }
    const double focal = calib[0][0];
    const cv::Point2d pp(calib[0][2], calib[0][6]);

    // The frame sequence as the camera delivers it: a duplicated frame comes twice (a stop).
    std::vector<int> sequence;
    for (int f = 0; f < frames && f < static_cast<int>(poses.size()); ++f) {
        sequence.push_back(f);
        if (duplicated.count(f))
            sequence.push_back(f);
    }

    cv::Ptr<cv::ORB> orb = cv::ORB::create(2000);
    cv::BFMatcher matcher(cv::NORM_HAMMING, true);
    std::vector<cv::KeyPoint> prevKeys;
    cv::Mat prevDescriptors;
    std::vector<double> errors;
    int emptyPairs = 0;
    for (size_t k = 0; k < sequence.size(); ++k) {
        char name[32];
        std::snprintf(name, sizeof(name), "/image_l/%06d.png", sequence[k]);
        const cv::Mat image = cv::imread(folder + name, cv::IMREAD_GRAYSCALE);
        if (image.empty()) {
            std::cerr << "cannot read " << folder << name << "\n";
            return 2;
        }
        std::vector<cv::KeyPoint> keys;
        cv::Mat descriptors;
        orb->detectAndCompute(image, cv::noArray(), keys, descriptors);
        if (k > 0) {
            std::vector<cv::DMatch> matches;
            matcher.match(descriptors, prevDescriptors, matches);
            std::vector<cv::Point2f> cur, prev;
            for (const cv::DMatch& m : matches) {
                cur.push_back(keys[m.queryIdx].pt);
                prev.push_back(prevKeys[m.trainIdx].pt);
            }
            // The two calls of the example, in OpenCV's idiom: no status, no check of E.
            cv::Mat E, R, t, mask;
            E = VO_NAMESPACE::findEssentialMat(cur, prev, focal, pp, cv::RANSAC, 0.999, 1.0, mask);
            const int inliers = VO_NAMESPACE::recoverPose(E, cur, prev, R, t, focal, pp, mask);
            if (inliers == 0)
                ++emptyPairs;
            // x_prev = R x_cur + t: R is the rotation of frame cur into frame prev.
            const cv::Mat truth = rotationOf(poses[static_cast<size_t>(sequence[k - 1])]).t() *
                                  rotationOf(poses[static_cast<size_t>(sequence[k])]);
            const double error = angleDeg(R.t() * truth);
            errors.push_back(error);
            std::printf("pair %d -> %d: %zu matches, %d inliers, rotation error %.4f deg\n",
                        sequence[k - 1], sequence[k], cur.size(), inliers, error);
        }
        prevKeys = keys;
        prevDescriptors = descriptors;
    }
    std::vector<double> sorted = errors;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted.empty() ? 0 : sorted[sorted.size() / 2];
    std::printf(
        "%s: %zu pairs, %d with no inliers, median rotation error: %.4f deg, max %.4f deg\n",
        VO_NAMESPACE_NAME, errors.size(), emptyPairs, median, sorted.empty() ? 0 : sorted.back());
    return 0;
}
