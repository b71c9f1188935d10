// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

/*
Two-view camera motion with cv::rcme on a real image pair.

Detects SIFT features in two images, matches them (brute force, k = 2, Lowe's ratio test 0.8),
estimates the relative motion with cv::rcme::recoverPose (or only the fundamental matrix with
cv::rcme::findFundamentalMat when no camera matrix is given), compares it with the ground truth
when one is given, and writes a side-by-side picture of the inlier and outlier matches with a few
epipolar lines.

Without image arguments it runs on the bundled pair of samples/data (fountain-P11, see
samples/data/PROVENANCE.md) with its camera matrix and ground-truth pose.

Exit codes: 0 success; 1 the estimation did not succeed (non-success status) or the rotation
error exceeds --max-rotation-error-deg; 2 usage or input/output error; 3 error raised by the
library (cv::Exception, e.g. a method that is not implemented).
*/

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rcme.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef RCME_SAMPLES_DATA_DIR
#define RCME_SAMPLES_DATA_DIR "samples/data"
#endif

namespace {

const char* const kDefaultImage1 = "fountain_0004.jpg";
const char* const kDefaultImage2 = "fountain_0006.jpg";
const char* const kDefaultK = "K.txt";
const char* const kDefaultGt = "pose_gt.txt";

enum ExitCode
{
    EXIT_OK = 0,
    EXIT_NOT_SUCCESS = 1,
    EXIT_USAGE = 2,
    EXIT_LIBRARY_ERROR = 3
};

//! Usage or input/output error: reported with exit code 2.
struct UsageError : std::runtime_error
{
    explicit UsageError(const std::string& what) : std::runtime_error(what) {}
};

void printUsage(const char* argv0)
{
    std::cout
        << "Usage: " << argv0 << " [options] [img1 img2]\n"
        << "\n"
        << "Estimates the camera motion between two images with cv::rcme (SIFT + ratio test).\n"
        << "Without images, runs on the bundled pair of " << RCME_SAMPLES_DATA_DIR << "\n"
        << "with its camera matrix and ground-truth pose.\n"
        << "\n"
        << "Options (--key value or --key=value):\n"
        << "  --method M      standard (default), rcme, prcme, mlesac, cov-ransac\n"
        << "  --solver S      eight (default), seven, five\n"
        << "  --k FILE        3x3 camera matrix (9 numbers); 'none' estimates only F.\n"
        << "                  Default: the bundled K.txt without images, none with images.\n"
        << "  --gt FILE       ground truth: R (3 rows) then unit t, x2 = R x1 + t; 'none'\n"
        << "                  to skip. Default: the bundled pose_gt.txt without images.\n"
        << "  --data DIR      directory of the bundled pair (default " << RCME_SAMPLES_DATA_DIR
        << ")\n"
        << "  --out FILE      output PNG (default rcme_two_view_demo.png)\n"
        << "  --sigma S       noise sigma in pixels (Params::sigma, default 1)\n"
        << "  --threshold T   inlier threshold in pixels (Params::threshold, default: from "
           "sigma)\n"
        << "  --seed N        random generator state (default 0)\n"
        << "  --max-rotation-error-deg X\n"
        << "                  exit with 1 when the rotation error w.r.t. the ground truth\n"
        << "                  exceeds X degrees (needs a camera matrix and ground truth)\n"
        << "  -h, --help      this help\n"
        << "\n"
        << "Exit codes: 0 success; 1 estimation not successful or rotation error too large;\n"
        << "2 usage or input/output error; 3 error raised by the library.\n";
}

struct Options
{
    std::string method = "standard";
    std::string solver = "eight";
    std::string kPath;  // empty: default, "none": uncalibrated
    std::string gtPath; // empty: default, "none": no ground truth
    std::string dataDir = RCME_SAMPLES_DATA_DIR;
    std::string outPath = "rcme_two_view_demo.png";
    double sigma = 1.0;
    double threshold = 0.0;
    int seed = 0;
    double maxRotationErrorDeg = -1.0;
    std::vector<std::string> images;
    bool help = false;
};

double parseDouble(const std::string& key, const std::string& value)
{
    try {
        size_t used = 0;
        double v = std::stod(value, &used);
        if (used == value.size() && std::isfinite(v))
            return v;
    } catch (const std::exception&) {
    }
    throw UsageError("--" + key + " expects a number, got '" + value + "'");
}

int parseInt(const std::string& key, const std::string& value)
{
    try {
        size_t used = 0;
        int v = std::stoi(value, &used);
        if (used == value.size())
            return v;
    } catch (const std::exception&) {
    }
    throw UsageError("--" + key + " expects an integer, got '" + value + "'");
}

Options parseArgs(int argc, char** argv)
{
    Options opt;
    const std::vector<std::string> valueKeys = {
        "method", "solver", "k",         "gt",   "data",
        "out",    "sigma",  "threshold", "seed", "max-rotation-error-deg"};
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "-h" || arg == "--help" || arg == "-help" || arg == "-?") {
            opt.help = true;
            continue;
        }
        if (arg.size() < 2 || arg[0] != '-' || arg == "--") {
            opt.images.push_back(arg);
            continue;
        }
        std::string key = arg.substr(arg[1] == '-' ? 2 : 1);
        std::string value;
        const size_t eq = key.find('=');
        if (eq != std::string::npos) {
            value = key.substr(eq + 1);
            key = key.substr(0, eq);
        } else {
            if (std::find(valueKeys.begin(), valueKeys.end(), key) == valueKeys.end())
                throw UsageError("unknown option '" + arg + "' (see --help)");
            if (i + 1 >= argc)
                throw UsageError("option --" + key + " needs a value");
            value = argv[++i];
        }
        if (key == "method")
            opt.method = value;
        else if (key == "solver")
            opt.solver = value;
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
        else
            throw UsageError("unknown option '" + arg + "' (see --help)");
    }
    if (!opt.images.empty() && opt.images.size() != 2)
        throw UsageError("expected two images (img1 img2) or none, got " +
                         std::to_string(opt.images.size()));
    if (opt.outPath.empty())
        throw UsageError("--out needs a file name");
    return opt;
}

cv::rcme::Method parseMethod(const std::string& name)
{
    static const std::map<std::string, cv::rcme::Method> methods = {
        {"standard", cv::rcme::METHOD_STANDARD},     {"rcme", cv::rcme::METHOD_RCME},
        {"prcme", cv::rcme::METHOD_PRCME},           {"mlesac", cv::rcme::METHOD_MLESAC},
        {"cov-ransac", cv::rcme::METHOD_COV_RANSAC}, {"cov_ransac", cv::rcme::METHOD_COV_RANSAC},
        {"covransac", cv::rcme::METHOD_COV_RANSAC}};
    auto it = methods.find(name);
    if (it == methods.end())
        throw UsageError("unknown --method '" + name +
                         "' (standard, rcme, prcme, mlesac, cov-ransac)");
    return it->second;
}

cv::rcme::MinimalSolverKind parseSolver(const std::string& name)
{
    if (name == "eight" || name == "8")
        return cv::rcme::SOLVER_EIGHT_POINT;
    if (name == "seven" || name == "7")
        return cv::rcme::SOLVER_SEVEN_POINT;
    if (name == "five" || name == "5")
        return cv::rcme::SOLVER_FIVE_POINT;
    throw UsageError("unknown --solver '" + name + "' (eight, seven, five)");
}

//! Reads whitespace-separated numbers; '#' starts a comment that runs to the end of the line.
std::vector<double> readNumbers(const std::string& path, size_t expected, const char* what)
{
    std::ifstream in(path);
    if (!in)
        throw UsageError(std::string("cannot open ") + what + " file '" + path + "'");
    std::vector<double> values;
    std::string line;
    while (std::getline(in, line)) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos)
            line.resize(hash);
        std::istringstream ss(line);
        std::string token;
        while (ss >> token) {
            try {
                size_t used = 0;
                double v = std::stod(token, &used);
                if (used != token.size() || !std::isfinite(v))
                    throw std::invalid_argument(token);
                values.push_back(v);
            } catch (const std::exception&) {
                throw UsageError(std::string("bad number '") + token + "' in " + what + " file '" +
                                 path + "'");
            }
        }
    }
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
        return "the samples or the selected model were degenerate (identical or collinear "
               "points, pure rotation, or a motion that cheirality cannot resolve)";
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

std::string fixed(double v, int digits)
{
    std::ostringstream ss;
    ss.setf(std::ios::fixed);
    ss.precision(digits);
    ss << v;
    return ss.str();
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

    const cv::Mat img1 = readImage(path1), img2 = readImage(path2);
    cv::Mat K, Rgt, tgt;
    if (!kPath.empty())
        K = readCameraMatrix(kPath);
    if (!gtPath.empty())
        readGroundTruth(gtPath, Rgt, tgt);
    if (opt.maxRotationErrorDeg >= 0 && (K.empty() || Rgt.empty()))
        throw UsageError("--max-rotation-error-deg needs a camera matrix (--k) and a ground "
                         "truth (--gt)");

    std::cout << "image 1: " << path1 << " (" << img1.cols << "x" << img1.rows << ")\n"
              << "image 2: " << path2 << " (" << img2.cols << "x" << img2.rows << ")\n"
              << "camera matrix: " << (kPath.empty() ? "none (fundamental matrix only)" : kPath)
              << "\n"
              << "ground truth: " << (gtPath.empty() ? "none" : gtPath) << "\n"
              << "method: " << opt.method << ", solver: " << opt.solver
              << ", sigma: " << params.sigma << " px, seed: " << params.randomGeneratorState
              << "\n";

    // Features and matches: SIFT, brute force k = 2, Lowe's ratio test 0.8.
    cv::TickMeter tmFeatures;
    tmFeatures.start();
    cv::Ptr<cv::SIFT> sift = cv::SIFT::create();
    std::vector<cv::KeyPoint> kp1, kp2;
    cv::Mat desc1, desc2;
    sift->detectAndCompute(img1, cv::noArray(), kp1, desc1);
    sift->detectAndCompute(img2, cv::noArray(), kp2, desc2);
    std::vector<cv::Point2f> pts1, pts2;
    if (!desc1.empty() && !desc2.empty()) {
        cv::BFMatcher matcher(cv::NORM_L2);
        std::vector<std::vector<cv::DMatch>> knn;
        matcher.knnMatch(desc1, desc2, knn, 2);
        for (const auto& m : knn)
            if (m.size() == 2 && m[0].distance < 0.8f * m[1].distance) {
                pts1.push_back(kp1[m[0].queryIdx].pt);
                pts2.push_back(kp2[m[0].trainIdx].pt);
            }
    }
    tmFeatures.stop();
    std::cout << "keypoints: " << kp1.size() << " / " << kp2.size()
              << ", matches after ratio test: " << pts1.size() << " ("
              << fixed(tmFeatures.getTimeMilli(), 1) << " ms)\n";

    // Robust estimation.
    cv::Mat E, R, t, F, mask, covariance;
    cv::rcme::Status status = cv::rcme::STATUS_SUCCESS;
    int inliers = 0;
    cv::TickMeter tm;
    tm.start();
    if (!K.empty()) {
        inliers = cv::rcme::recoverPose(pts1, pts2, K, E, R, t, params, mask, status, covariance);
    } else {
        F = cv::rcme::findFundamentalMat(pts1, pts2, params, mask, status);
        inliers = mask.empty() ? 0 : cv::countNonZero(mask);
    }
    tm.stop();
    if (status == cv::rcme::STATUS_SUCCESS && !E.empty()) {
        const cv::Mat Kinv = K.inv();
        F = Kinv.t() * E * Kinv;
        F /= cv::norm(F);
    }

    std::cout << "status: " << cv::rcme::statusToString(status) << "\n"
              << "time: " << fixed(tm.getTimeMilli(), 2) << " ms\n";
    if (status == cv::rcme::STATUS_SUCCESS) {
        std::cout << "inliers: " << inliers << " / " << pts1.size()
                  << (K.empty() ? "" : " (passing cheirality)") << "\n"
                  << "F = " << formatMat(F) << "\n";
        if (!K.empty())
            std::cout << "R = " << formatMat(R) << "\n"
                      << "t = " << formatMat(t.t()) << "^T\n";
        if (covariance.rows == 5 && covariance.cols == 5) {
            cv::Mat sd;
            cv::sqrt(covariance.diag(), sd);
            std::cout << "std of the rotation increment (deg): "
                      << fixed(sd.at<double>(0) * 180 / CV_PI, 4) << " "
                      << fixed(sd.at<double>(1) * 180 / CV_PI, 4) << " "
                      << fixed(sd.at<double>(2) * 180 / CV_PI, 4)
                      << ", of the translation direction (deg): "
                      << fixed(sd.at<double>(3) * 180 / CV_PI, 4) << " "
                      << fixed(sd.at<double>(4) * 180 / CV_PI, 4) << "\n";
        }
    } else {
        std::cout << "estimation failed: " << statusExplanation(status) << "\n";
    }

    double rotationErrorDeg = -1, translationErrorDeg = -1;
    if (status == cv::rcme::STATUS_SUCCESS && !R.empty() && !Rgt.empty()) {
        const cv::rcme::MotionError err = cv::rcme::compareMotion(R, t, Rgt, tgt);
        rotationErrorDeg = err.rotationDeg;
        translationErrorDeg = err.translationDeg;
        std::cout << "rotation error: " << fixed(rotationErrorDeg, 3) << " deg\n"
                  << "translation direction error: " << fixed(translationErrorDeg, 3) << " deg\n";
    } else if (!Rgt.empty() && K.empty()) {
        std::cout << "ground truth given but no camera matrix: motion errors not computed\n";
    }

    // Picture.
    std::vector<std::string> header;
    header.push_back("cv::rcme, method " + opt.method + ": " + cv::rcme::statusToString(status) +
                     ", " + std::to_string(inliers) + " / " + std::to_string(pts1.size()) +
                     " matches are inliers, " + fixed(tm.getTimeMilli(), 1) + " ms");
    if (rotationErrorDeg >= 0)
        header.push_back("error vs ground truth: rotation " + fixed(rotationErrorDeg, 2) +
                         " deg, translation direction " + fixed(translationErrorDeg, 2) + " deg");
    header.push_back("green: inliers, red: outliers (at most 150 lines each)" +
                     std::string(F.empty() ? "" : ", colours: epipolar lines of 8 inliers"));
    const cv::Mat canvas = drawMatches(img1, img2, pts1, pts2, mask, F, header);
    const std::filesystem::path outPath = std::filesystem::absolute(opt.outPath);
    std::error_code ec;
    if (outPath.has_parent_path())
        std::filesystem::create_directories(outPath.parent_path(), ec);
    bool written = false;
    try {
        written = cv::imwrite(outPath.string(), canvas);
    } catch (const cv::Exception& e) {
        throw UsageError("cannot write '" + outPath.string() + "': " + e.what());
    }
    if (!written)
        throw UsageError("cannot write '" + outPath.string() + "'");
    std::cout << "wrote " << outPath.string() << "\n";

    if (status != cv::rcme::STATUS_SUCCESS)
        return EXIT_NOT_SUCCESS;
    if (opt.maxRotationErrorDeg >= 0 && !(rotationErrorDeg <= opt.maxRotationErrorDeg)) {
        std::cout << "FAILED: rotation error " << fixed(rotationErrorDeg, 3)
                  << " deg exceeds --max-rotation-error-deg " << opt.maxRotationErrorDeg << "\n";
        return EXIT_NOT_SUCCESS;
    }
    return EXIT_OK;
}

} // namespace

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << "\n(run with --help for the usage)\n";
        return EXIT_USAGE;
    } catch (const cv::Exception& e) {
        std::cerr << "OpenCV error: " << e.what() << "\n";
        return EXIT_LIBRARY_ERROR;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return EXIT_LIBRARY_ERROR;
    }
}
