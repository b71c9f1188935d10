// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

/*
Two-view camera motion with cv::rcme on a real image pair.

Detects SIFT features in two images, matches them (brute force, k = 2, Lowe's ratio test 0.8),
estimates the relative motion with cv::rcme::recoverPose (or only the fundamental matrix with
cv::rcme::findFundamentalMat when no camera matrix is given) and, on the same matches, with
OpenCV's own estimator (cv::findEssentialMat RANSAC + cv::recoverPose, or cv::findFundamentalMat
FM_RANSAC), compares both with the ground truth when one is given, and writes a picture with one
row per estimator: the inlier and outlier matches and a few epipolar lines.

Without image arguments it runs on the bundled pair of samples/data (fountain-P11, see
samples/data/PROVENANCE.md) with its camera matrix and ground-truth pose.

Exit codes: 0 success; 1 the estimation did not succeed (non-success status) or the rotation
error exceeds --max-rotation-error-deg; 2 usage or input/output error; 3 error raised by the
library (cv::Exception, e.g. a method that is not implemented).
*/

#include "sample_common.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rcme.hpp>
#include <opencv2/rcme/opencv_geometry.hpp> // cv::findEssentialMat & co.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#ifndef RCME_SAMPLES_DATA_DIR
#define RCME_SAMPLES_DATA_DIR "samples/data"
#endif

namespace {

using namespace rcme_samples;

const char* const kDefaultImage1 = "fountain_0004.jpg";
const char* const kDefaultImage2 = "fountain_0006.jpg";
const char* const kDefaultK = "K.txt";
const char* const kDefaultGt = "pose_gt.txt";

void printUsage(const char* argv0)
{
    std::cout
        << "Usage: " << argv0 << " [options] [img1 img2]\n"
        << "\n"
        << "Estimates the camera motion between two images with cv::rcme (SIFT + ratio test)\n"
        << "and, on the same matches, with OpenCV's estimator; draws both side by side.\n"
        << "Without images, runs on the bundled pair of " << RCME_SAMPLES_DATA_DIR << "\n"
        << "with its camera matrix and ground-truth pose.\n"
        << "\n"
        << "Options (--key value or --key=value):\n"
        << "  --method M      rcme's method: " << methodNames() << "\n"
        << "                  (default standard)\n"
        << "  --solver S      auto (default: five with K, else eight), eight, seven, five\n"
        << "  --opencv-method O  essential (findEssentialMat RANSAC + recoverPose; needs a\n"
        << "                  camera matrix), fundamental (findFundamentalMat FM_RANSAC), or\n"
        << "                  none. Default: essential with a camera matrix, else fundamental.\n"
        << "  --opencv-threshold T  OpenCV's inlier threshold in pixels (default: rcme's)\n"
        << "  --k FILE        3x3 camera matrix (9 numbers); 'none' estimates only F.\n"
        << "                  Default: the bundled K.txt without images, none with images.\n"
        << "  --gt FILE       ground truth: R (3 rows) then unit t, x2 = R x1 + t; 'none'\n"
        << "                  to skip. Default: the bundled pose_gt.txt without images.\n"
        << "  --data DIR      directory of the bundled pair (default " << RCME_SAMPLES_DATA_DIR
        << ")\n"
        << "  --out FILE      output picture, PNG (default rcme_two_view_demo.png) or, by\n"
        << "                  its extension, JPEG\n"
        << "  --picture-width W\n"
        << "                  scale the picture to W pixels wide (default 0: natural size)\n"
        << "  --sigma S       noise sigma in pixels (Params::sigma, default 1)\n"
        << "  --threshold T   inlier threshold in pixels (Params::threshold, default: from "
           "sigma)\n"
        << "  --seed N        rcme's random generator state (default 0; OpenCV's RANSAC has a\n"
        << "                  fixed internal seed)\n"
        << "  --max-rotation-error-deg X\n"
        << "                  exit with 1 when rcme's rotation error w.r.t. the ground truth\n"
        << "                  exceeds X degrees (needs a camera matrix and ground truth)\n"
        << "  -h, --help      this help\n"
        << "\n"
        << "Exit codes (from rcme's result; OpenCV's is only shown): 0 success; 1 estimation\n"
        << "not successful or rotation error too large; 2 usage or input/output error; 3 error\n"
        << "raised by the library.\n";
}

struct Options
{
    std::string method = "standard";
    std::string solver = "auto";
    std::string opencvMethod;     // empty: essential with a camera matrix, else fundamental
    double opencvThreshold = 0.0; // <= 0: the same as rcme's
    std::string kPath;            // empty: default, "none": uncalibrated
    std::string gtPath;           // empty: default, "none": no ground truth
    std::string dataDir = RCME_SAMPLES_DATA_DIR;
    std::string outPath = "rcme_two_view_demo.png";
    double sigma = 1.0;
    double threshold = 0.0;
    int seed = 0;
    double maxRotationErrorDeg = -1.0;
    int pictureWidth = 0; // 0: natural size
    std::vector<std::string> images;
    bool help = false;
};

Options parseArgs(int argc, char** argv)
{
    const CommandLine cmd(argc, argv,
                          {"method", "solver", "opencv-method", "opencv-threshold", "k", "gt",
                           "data", "out", "sigma", "threshold", "seed", "max-rotation-error-deg",
                           "picture-width"});
    Options opt;
    opt.help = cmd.help;
    opt.images = cmd.positional;
    for (const auto& [key, value] : cmd.options) {
        if (key == "method")
            opt.method = value;
        else if (key == "solver")
            opt.solver = value;
        else if (key == "opencv-method")
            opt.opencvMethod = value;
        else if (key == "opencv-threshold")
            opt.opencvThreshold = parseDouble(key, value);
        else if (key == "k")
            opt.kPath = value;
        else if (key == "gt")
            opt.gtPath = value;
        else if (key == "data")
            opt.dataDir = value;
        else if (key == "out")
            opt.outPath = value;
        else if (key == "sigma")
            opt.sigma = parseDouble(key, value);
        else if (key == "threshold")
            opt.threshold = parseDouble(key, value);
        else if (key == "seed")
            opt.seed = parseInt(key, value);
        else if (key == "max-rotation-error-deg")
            opt.maxRotationErrorDeg = parseDouble(key, value);
        else if (key == "picture-width")
            opt.pictureWidth = parseInt(key, value);
    }
    if (!opt.images.empty() && opt.images.size() != 2)
        throw UsageError("expected two images (img1 img2) or none, got " +
                         std::to_string(opt.images.size()));
    if (opt.outPath.empty())
        throw UsageError("--out needs a file name");
    if (opt.pictureWidth < 0)
        throw UsageError("--picture-width must be >= 0");
    if (!opt.opencvMethod.empty() && opt.opencvMethod != "essential" &&
        opt.opencvMethod != "fundamental" && opt.opencvMethod != "none")
        throw UsageError("unknown --opencv-method '" + opt.opencvMethod +
                         "' (essential, fundamental, none)");
    return opt;
}

//! All the numbers of a small text file, in reading order.
std::vector<double> readNumbers(const std::string& path, size_t expected, const char* what)
{
    std::vector<double> values;
    for (const auto& row : readNumberRows(path, what))
        values.insert(values.end(), row.begin(), row.end());
    if (values.size() != expected)
        throw UsageError(std::string(what) + " file '" + path + "' must hold " +
                         std::to_string(expected) + " numbers, found " +
                         std::to_string(values.size()));
    return values;
}

cv::Mat readCameraMatrix(const std::string& path)
{
    std::vector<double> v = readNumbers(path, 9, "camera matrix");
    cv::Mat K = cv::Mat(v, true).reshape(1, 3);
    if (std::abs(cv::determinant(K)) < 1e-12)
        throw UsageError("camera matrix in '" + path + "' is singular");
    return K;
}

void readGroundTruth(const std::string& path, cv::Mat& R, cv::Mat& t)
{
    std::vector<double> v = readNumbers(path, 12, "ground-truth pose");
    R = cv::Mat(std::vector<double>(v.begin(), v.begin() + 9), true).reshape(1, 3);
    t = cv::Mat(std::vector<double>(v.begin() + 9, v.end()), true);
    if (cv::norm(R * R.t(), cv::Mat::eye(3, 3, CV_64F), cv::NORM_INF) > 1e-4 ||
        cv::determinant(R) < 0)
        throw UsageError("R in ground-truth file '" + path + "' is not a rotation");
    const double tn = cv::norm(t);
    if (tn < 1e-12)
        throw UsageError("t in ground-truth file '" + path + "' is zero");
    t /= tn;
}

cv::Mat readImage(const std::string& path)
{
    if (!std::filesystem::exists(path))
        throw UsageError("image not found: '" + path + "'");
    cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (img.empty())
        throw UsageError("cannot read image '" + path + "' (not an image or unsupported format)");
    return img;
}

std::string joinPath(const std::string& dir, const std::string& file)
{
    return (std::filesystem::path(dir) / file).string();
}

std::string formatMat(const cv::Mat& m)
{
    cv::Ptr<cv::Formatter> f = cv::Formatter::get(cv::Formatter::FMT_DEFAULT);
    f->set64fPrecision(6);
    std::ostringstream ss;
    ss << f->format(m);
    std::string s = ss.str();
    // indent continuation lines for readability
    std::string out;
    for (char c : s) {
        out += c;
        if (c == '\n')
            out += "    ";
    }
    return out;
}

const char* statusExplanation(cv::rcme::Status status)
{
    switch (status) {
    case cv::rcme::STATUS_SUCCESS:
        return "a model was found";
    case cv::rcme::STATUS_POOR_QUALITY_INPUT:
        return "no hypothesis passed the method's acceptance tests: the matches are too poor to "
               "trust any motion computed from them";
    case cv::rcme::STATUS_NOT_ENOUGH_POINTS:
        return "fewer valid correspondences than the minimal solver needs";
    case cv::rcme::STATUS_DEGENERATE_CONFIGURATION:
        return "the configuration does not determine the motion: a homography explains the "
               "inliers as well as F without a camera matrix (planar scene, pure rotation or too "
               "little parallax), two motions of a planar scene remain, the samples were "
               "degenerate (identical or collinear points), or cheirality cannot resolve the "
               "motion";
    case cv::rcme::STATUS_PURE_ROTATION:
        return "the camera only rotated: R is determined, the translation is not (t is zero)";
    case cv::rcme::STATUS_UNDETERMINED_MOTION:
        return "the inliers do not determine the motion to the accuracy asked: a distinct motion "
               "explains them about as well, or its uncertainty exceeds the bound";
    }
    return "unknown status";
}

//! Two points where the line a x + b y + c = 0 crosses the image rectangle; false if it misses.
bool lineInImage(const cv::Vec3d& l, const cv::Size& size, cv::Point& p1, cv::Point& p2)
{
    const double a = l[0], b = l[1], c = l[2];
    const double big = 4.0 * (size.width + size.height);
    cv::Point2d q1, q2;
    if (std::abs(b) >= std::abs(a)) { // closer to horizontal: intersect x = -big and x = big
        if (std::abs(b) < 1e-300)
            return false;
        q1 = cv::Point2d(-big, -(c - a * big) / b);
        q2 = cv::Point2d(big, -(c + a * big) / b);
    } else { // closer to vertical: intersect y = -big and y = big
        q1 = cv::Point2d(-(c - b * big) / a, -big);
        q2 = cv::Point2d(-(c + b * big) / a, big);
    }
    const double limit = 1e9; // far outside the image: no intersection, avoids int overflow
    if (!(std::abs(q1.x) < limit && std::abs(q1.y) < limit && std::abs(q2.x) < limit &&
          std::abs(q2.y) < limit))
        return false;
    cv::Point2l r1(cvRound(q1.x), cvRound(q1.y)), r2(cvRound(q2.x), cvRound(q2.y));
    if (!cv::clipLine(cv::Size2l(size.width, size.height), r1, r2))
        return false;
    p1 = cv::Point(static_cast<int>(r1.x), static_cast<int>(r1.y));
    p2 = cv::Point(static_cast<int>(r2.x), static_cast<int>(r2.y));
    return true;
}

cv::Mat drawMatches(const cv::Mat& img1, const cv::Mat& img2, const std::vector<cv::Point2f>& pts1,
                    const std::vector<cv::Point2f>& pts2, const cv::Mat& mask, const cv::Mat& F,
                    const std::vector<std::string>& header)
{
    const int lineHeight = 20;
    const int bannerHeight = lineHeight * static_cast<int>(header.size()) + 8;
    const int width = img1.cols + img2.cols;
    const int height = std::max(img1.rows, img2.rows);
    cv::Mat canvas(height + bannerHeight, width, CV_8UC3, cv::Scalar::all(0));
    const cv::Point off1(0, bannerHeight), off2(img1.cols, bannerHeight);
    cv::cvtColor(img1, canvas(cv::Rect(off1, img1.size())), cv::COLOR_GRAY2BGR);
    cv::cvtColor(img2, canvas(cv::Rect(off2, img2.size())), cv::COLOR_GRAY2BGR);

    const cv::Scalar green(0, 200, 0), red(0, 0, 255);
    const int shift = 4; // sub-pixel drawing
    auto fx = [&](const cv::Point2f& p, const cv::Point& off) {
        return cv::Point(cvRound((p.x + off.x) * (1 << shift)),
                         cvRound((p.y + off.y) * (1 << shift)));
    };

    std::vector<int> inliers, outliers;
    for (size_t i = 0; i < pts1.size(); ++i)
        (!mask.empty() && mask.at<uchar>(static_cast<int>(i)) ? inliers : outliers)
            .push_back(static_cast<int>(i));

    // Match lines, subsampled so that the picture stays readable, and blended over the images.
    // Every inlier keypoint is marked with a small circle.
    const size_t maxLines = 150;
    auto step = [&](size_t n) { return std::max<size_t>(1, (n + maxLines - 1) / maxLines); };
    cv::Mat lines = canvas.clone();
    const size_t outStep = step(outliers.size()), inStep = step(inliers.size());
    for (size_t k = 0; k < outliers.size(); k += outStep) {
        const int i = outliers[k];
        cv::line(lines, fx(pts1[i], off1), fx(pts2[i], off2), red, 1, cv::LINE_AA, shift);
    }
    for (size_t k = 0; k < inliers.size(); k += inStep) {
        const int i = inliers[k];
        cv::line(lines, fx(pts1[i], off1), fx(pts2[i], off2), green, 1, cv::LINE_AA, shift);
    }
    cv::addWeighted(lines, 0.7, canvas, 0.3, 0.0, canvas);
    for (int i : inliers) {
        cv::circle(canvas, fx(pts1[i], off1), 2 << shift, green, 1, cv::LINE_AA, shift);
        cv::circle(canvas, fx(pts2[i], off2), 2 << shift, green, 1, cv::LINE_AA, shift);
    }

    // a few epipolar lines through inliers spread over the list, in both images
    if (!F.empty() && !inliers.empty()) {
        const cv::Scalar palette[] = {{255, 255, 0},   {255, 0, 255},  {0, 255, 255},
                                      {255, 128, 0},   {128, 0, 255},  {0, 128, 255},
                                      {255, 255, 255}, {128, 255, 128}};
        const int numLines = static_cast<int>(std::min<size_t>(8, inliers.size()));
        for (int k = 0; k < numLines; ++k) {
            const int i =
                inliers[(k * inliers.size()) / numLines + inliers.size() / (2 * numLines)];
            const cv::Scalar& color = palette[k % 8];
            const cv::Vec3d x1(pts1[i].x, pts1[i].y, 1.0), x2(pts2[i].x, pts2[i].y, 1.0);
            const cv::Matx33d Fm(F);
            const cv::Vec3d l2 = Fm * x1, l1 = Fm.t() * x2;
            cv::Point a, b;
            if (lineInImage(l2, img2.size(), a, b))
                cv::line(canvas, a + off2, b + off2, color, 2, cv::LINE_AA);
            if (lineInImage(l1, img1.size(), a, b))
                cv::line(canvas, a + off1, b + off1, color, 2, cv::LINE_AA);
            cv::circle(canvas, fx(pts1[i], off1), 5 << shift, color, 2, cv::LINE_AA, shift);
            cv::circle(canvas, fx(pts2[i], off2), 5 << shift, color, 2, cv::LINE_AA, shift);
        }
    }

    for (size_t k = 0; k < header.size(); ++k)
        cv::putText(canvas, header[k], cv::Point(8, lineHeight * static_cast<int>(k + 1)),
                    cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar::all(255), 1, cv::LINE_AA);
    return canvas;
}

//! One estimator's result on the matches, as drawn in one row of the picture.
struct Estimate
{
    std::string name;     //!< e.g. "cv::rcme::recoverPose, method rcme"
    bool success = false; //!< rcme: STATUS_SUCCESS; OpenCV: a model was returned
    std::string outcome;  //!< status text
    cv::Mat F, R, t, mask;
    int inliers = 0;
    bool inliersPassCheirality = false; //!< the mask is recoverPose's
    double milliseconds = 0;
    double rotationErrorDeg = -1, translationErrorDeg = -1;
    //! rcme with K: the covariance's standard deviations (rotation: norm of the per-axis ones)
    double rotationStdDeg = -1, translationStdDeg = -1;
};

Estimate estimateWithRcme(const std::vector<cv::Point2f>& pts1,
                          const std::vector<cv::Point2f>& pts2, const cv::Mat& K,
                          const cv::rcme::Params& params, const std::string& methodName)
{
    Estimate est;
    cv::Mat E, covariance;
    cv::rcme::Status status = cv::rcme::STATUS_SUCCESS;
    cv::TickMeter tm;
    tm.start();
    if (!K.empty()) {
        est.name = "cv::rcme::recoverPose, method " + methodName;
        est.inliersPassCheirality = true;
        est.inliers = cv::rcme::recoverPose(pts1, pts2, K, E, est.R, est.t, params, est.mask,
                                            status, covariance);
    } else {
        est.name = "cv::rcme::findFundamentalMat, method " + methodName;
        est.F = cv::rcme::findFundamentalMat(pts1, pts2, params, est.mask, status);
        est.inliers = est.mask.empty() ? 0 : cv::countNonZero(est.mask);
    }
    tm.stop();
    est.milliseconds = tm.getTimeMilli();
    est.success = status == cv::rcme::STATUS_SUCCESS;
    est.outcome = cv::rcme::statusToString(status);
    if (est.success && !E.empty()) {
        const cv::Mat Kinv = K.inv();
        est.F = Kinv.t() * E * Kinv;
        est.F /= cv::norm(est.F);
    }

    std::cout << "\n[" << est.name << "]\n"
              << "status: " << est.outcome << "\n"
              << "time: " << fixed(est.milliseconds, 2) << " ms\n";
    if (!est.success) {
        std::cout << "estimation failed: " << statusExplanation(status) << "\n";
        return est;
    }
    if (covariance.rows == 5 && covariance.cols == 5) {
        // The report's figures for the same estimate (a second run: same seed, same result).
        const cv::rcme::Report report = cv::rcme::estimateRelativeMotion(pts1, pts2, K, params);
        if (report.status == cv::rcme::STATUS_SUCCESS && !report.rotationStdDeg.empty()) {
            est.rotationStdDeg = cv::norm(report.rotationStdDeg);
            est.translationStdDeg = report.translationStdDeg;
            std::cout << "noise estimated from the inliers: " << fixed(report.noiseSigma, 2)
                      << " px\n"
                      << "std of the rotation about camera 1's x, y, z (deg): "
                      << fixed(report.rotationStdDeg.at<double>(0), 4) << " "
                      << fixed(report.rotationStdDeg.at<double>(1), 4) << " "
                      << fixed(report.rotationStdDeg.at<double>(2), 4)
                      << ", of the translation direction (deg, largest): "
                      << fixed(report.translationStdDeg, 4) << "\n";
        }
    }
    return est;
}

/** OpenCV's estimator on the same matches: findEssentialMat (RANSAC) + recoverPose, or
findFundamentalMat (FM_RANSAC), whose F gives a motion through E = K^T F K when K is known. */
Estimate estimateWithOpencv(const std::vector<cv::Point2f>& pts1,
                            const std::vector<cv::Point2f>& pts2, const cv::Mat& K,
                            const std::string& method, double threshold, double confidence)
{
    Estimate est;
    cv::TickMeter tm;
    tm.start();
    cv::Mat E;
    if (method == "essential") {
        est.name = "OpenCV findEssentialMat RANSAC + recoverPose";
        if (pts1.size() >= 5)
            E = cv::findEssentialMat(pts1, pts2, K, cv::RANSAC, confidence, threshold, est.mask);
    } else {
        est.name = "OpenCV findFundamentalMat FM_RANSAC";
        if (pts1.size() >= 8)
            est.F =
                cv::findFundamentalMat(pts1, pts2, cv::FM_RANSAC, threshold, confidence, est.mask);
        if (est.F.rows > 3)
            est.F = est.F.rowRange(0, 3).clone(); // the first of several solutions
        if (!est.F.empty() && !K.empty())
            E = K.t() * est.F * K;
    }
    if (E.rows > 3)
        E = E.rowRange(0, 3).clone(); // the first of several solutions
    if (!E.empty() && !K.empty()) {
        cv::Mat poseMask = est.mask.clone();
        est.inliers = cv::recoverPose(E, pts1, pts2, K, est.R, est.t, poseMask);
        if (method == "essential") {
            est.mask = poseMask; // as cv::recoverPose leaves it: inliers passing cheirality
            est.inliersPassCheirality = true;
            const cv::Mat Kinv = K.inv();
            est.F = Kinv.t() * E * Kinv;
        }
    }
    tm.stop();
    est.milliseconds = tm.getTimeMilli();
    if (method == "fundamental")
        est.inliers = est.mask.empty() ? 0 : cv::countNonZero(est.mask);
    if (!est.F.empty())
        est.F /= cv::norm(est.F);
    est.success = !est.F.empty();
    est.outcome = est.success ? "model returned" : "no model returned";
    if (est.mask.empty())
        est.mask = cv::Mat::zeros(static_cast<int>(pts1.size()), 1, CV_8U);
    std::cout << "\n[" << est.name << "]\n"
              << "result: " << est.outcome << " (OpenCV has no failure status)\n"
              << "time: " << fixed(est.milliseconds, 2) << " ms\n";
    return est;
}

//! Prints an estimate's model and its errors against the ground truth (when both are known).
void reportEstimate(Estimate& est, size_t numMatches, const cv::Mat& K, const cv::Mat& Rgt,
                    const cv::Mat& tgt)
{
    if (!est.success)
        return;
    std::cout << "inliers: " << est.inliers << " / " << numMatches
              << (est.inliersPassCheirality ? " (passing cheirality)" : "") << "\n"
              << "F = " << formatMat(est.F) << "\n";
    if (!est.R.empty())
        std::cout << "R = " << formatMat(est.R) << "\n"
                  << "t = " << formatMat(est.t.t()) << "^T\n";
    if (!est.R.empty() && !Rgt.empty()) {
        const cv::rcme::MotionError err = cv::rcme::compareMotion(est.R, est.t, Rgt, tgt);
        est.rotationErrorDeg = err.rotationDeg;
        est.translationErrorDeg = err.translationDeg;
        std::cout << "rotation error: " << fixed(est.rotationErrorDeg, 3) << " deg\n"
                  << "translation direction error: " << fixed(est.translationErrorDeg, 3)
                  << " deg\n";
    } else if (!Rgt.empty() && K.empty()) {
        std::cout << "ground truth given but no camera matrix: motion errors not computed\n";
    }
}

//! The banner lines of an estimate's row in the picture.
std::vector<std::string> bannerOf(const Estimate& est, size_t numMatches, double threshold)
{
    std::vector<std::string> header;
    header.push_back(est.name + ": " + est.outcome + ", " + std::to_string(est.inliers) + " / " +
                     std::to_string(numMatches) + " matches are inliers, " +
                     fixed(est.milliseconds, 1) + " ms, threshold " + fixed(threshold, 2) + " px");
    if (est.rotationErrorDeg >= 0)
        header.push_back("error vs ground truth: rotation " + fixed(est.rotationErrorDeg, 2) +
                         " deg, translation direction " + fixed(est.translationErrorDeg, 2) +
                         " deg");
    if (est.rotationStdDeg >= 0)
        header.push_back("predicted std (covariance): rotation " + fixed(est.rotationStdDeg, 3) +
                         " deg, translation direction " + fixed(est.translationStdDeg, 3) + " deg");
    header.push_back("green: inliers, red: outliers (at most 150 lines each)" +
                     std::string(est.F.empty() ? "" : ", colours: epipolar lines of 8 inliers"));
    return header;
}

int run(int argc, char** argv)
{
    const Options opt = parseArgs(argc, argv);
    if (opt.help) {
        printUsage(argv[0]);
        return EXIT_OK;
    }

    // Inputs: the bundled pair with its K and ground truth unless images are given.
    const bool bundled = opt.images.empty();
    const std::string path1 = bundled ? joinPath(opt.dataDir, kDefaultImage1) : opt.images[0];
    const std::string path2 = bundled ? joinPath(opt.dataDir, kDefaultImage2) : opt.images[1];
    std::string kPath = opt.kPath.empty() ? (bundled ? joinPath(opt.dataDir, kDefaultK) : "")
                                          : (opt.kPath == "none" ? "" : opt.kPath);
    std::string gtPath = opt.gtPath.empty() ? (bundled ? joinPath(opt.dataDir, kDefaultGt) : "")
                                            : (opt.gtPath == "none" ? "" : opt.gtPath);

    cv::rcme::Params params;
    params.method = parseMethod(opt.method);
    params.solver = parseSolver(opt.solver);
    params.sigma = opt.sigma;
    params.threshold = opt.threshold;
    params.randomGeneratorState = opt.seed;
    // rcme's inlier threshold: Params::threshold, or 1.96 sigma (chi2 with 1 DoF at 0.95)
    const double rcmeThreshold = opt.threshold > 0 ? opt.threshold : 1.959964 * opt.sigma;

    const cv::Mat img1 = readImage(path1), img2 = readImage(path2);
    cv::Mat K, Rgt, tgt;
    if (!kPath.empty())
        K = readCameraMatrix(kPath);
    if (!gtPath.empty())
        readGroundTruth(gtPath, Rgt, tgt);
    if (opt.maxRotationErrorDeg >= 0 && (K.empty() || Rgt.empty()))
        throw UsageError("--max-rotation-error-deg needs a camera matrix (--k) and a ground "
                         "truth (--gt)");
    const std::string opencvMethod =
        !opt.opencvMethod.empty() ? opt.opencvMethod : (K.empty() ? "fundamental" : "essential");
    if (opencvMethod == "essential" && K.empty())
        throw UsageError("--opencv-method essential needs a camera matrix (--k)");
    const double opencvThreshold = opt.opencvThreshold > 0 ? opt.opencvThreshold : rcmeThreshold;

    std::cout << "image 1: " << path1 << " (" << img1.cols << "x" << img1.rows << ")\n"
              << "image 2: " << path2 << " (" << img2.cols << "x" << img2.rows << ")\n"
              << "camera matrix: " << (kPath.empty() ? "none (fundamental matrix only)" : kPath)
              << "\n"
              << "ground truth: " << (gtPath.empty() ? "none" : gtPath) << "\n"
              << "method: " << opt.method << ", solver: " << opt.solver
              << ", sigma: " << params.sigma << " px, seed: " << params.randomGeneratorState << "\n"
              << "OpenCV: " << opencvMethod << ", threshold " << fixed(opencvThreshold, 2)
              << " px\n";

    // Features and matches: SIFT, brute force k = 2, Lowe's ratio test 0.8.
    cv::TickMeter tmFeatures;
    tmFeatures.start();
    cv::Ptr<cv::SIFT> sift = cv::SIFT::create();
    std::vector<cv::KeyPoint> kp1, kp2;
    cv::Mat desc1, desc2;
    sift->detectAndCompute(img1, cv::noArray(), kp1, desc1);
    sift->detectAndCompute(img2, cv::noArray(), kp2, desc2);
    const Matches matches = matchRatioTest(kp1, desc1, kp2, desc2);
    const std::vector<cv::Point2f>&pts1 = matches.points1, &pts2 = matches.points2;
    tmFeatures.stop();
    std::cout << "keypoints: " << kp1.size() << " / " << kp2.size()
              << ", matches after ratio test: " << pts1.size() << " ("
              << fixed(tmFeatures.getTimeMilli(), 1) << " ms)\n";

    // Robust estimation: rcme, then OpenCV on the same matches.
    std::vector<Estimate> estimates;
    estimates.push_back(estimateWithRcme(pts1, pts2, K, params, opt.method));
    reportEstimate(estimates.back(), pts1.size(), K, Rgt, tgt);
    if (opencvMethod != "none") {
        estimates.push_back(
            estimateWithOpencv(pts1, pts2, K, opencvMethod, opencvThreshold, params.confidence));
        reportEstimate(estimates.back(), pts1.size(), K, Rgt, tgt);
    }

    // Picture: one row per estimator, the same matches.
    std::vector<cv::Mat> rows;
    for (size_t k = 0; k < estimates.size(); ++k)
        rows.push_back(drawMatches(
            img1, img2, pts1, pts2, estimates[k].mask, estimates[k].F,
            bannerOf(estimates[k], pts1.size(), k == 0 ? rcmeThreshold : opencvThreshold)));
    cv::Mat canvas;
    cv::vconcat(rows, canvas);
    if (opt.pictureWidth > 0) // e.g. the smaller copy in doc/samples/
        cv::resize(canvas, canvas,
                   cv::Size(opt.pictureWidth, cvRound(static_cast<double>(canvas.rows) *
                                                      opt.pictureWidth / canvas.cols)),
                   0, 0, cv::INTER_AREA);
    std::cout << "\nwrote " << writePicture(opt.outPath, canvas) << "\n";

    const Estimate& rcmeEstimate = estimates.front();
    if (!rcmeEstimate.success)
        return EXIT_NOT_SUCCESS;
    if (opt.maxRotationErrorDeg >= 0 &&
        !(rcmeEstimate.rotationErrorDeg >= 0 &&
          rcmeEstimate.rotationErrorDeg <= opt.maxRotationErrorDeg)) {
        std::cout << "FAILED: rotation error " << fixed(rcmeEstimate.rotationErrorDeg, 3)
                  << " deg exceeds --max-rotation-error-deg " << opt.maxRotationErrorDeg << "\n";
        return EXIT_NOT_SUCCESS;
    }
    return EXIT_OK;
}

} // namespace

int main(int argc, char** argv)
{
    return runSample([&] { return run(argc, argv); });
}
