// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The OpenCV 4.6 forms of findFundamentalMat, findEssentialMat and recoverPose. Each maps its
// arguments onto Params the way OpenCV reads them (the same values accepted and rejected, see
// test_opencv_parity.cpp), runs the Params form, and answers failure as OpenCV code expects it:
// an empty matrix, or for recoverPose 0 points with a standing camera. Malformed arguments
// still raise cv::Exception naming them.

#include "precomp.hpp"

#include "drop_in/agreeing_points.hpp"
#include "drop_in/opencv_inlier_mask.hpp"
#include "framework/two_view_input.hpp"
#include "geometry/epipolar.hpp"

#include <opencv2/core/eigen.hpp>

#include <cfloat>

namespace cv {
namespace rcme {

namespace {

// OpenCV's defaults where it replaces an out-of-range argument.
constexpr double kFundamentalDefaultThreshold = 3.0; // findFundamentalMat, threshold <= 0
constexpr double kEssentialDefaultThreshold = 1.0;   // findEssentialMat's default argument
constexpr double kUsacDefaultThreshold = 1.5;        // cv::UsacParams().threshold
constexpr double kDefaultConfidence = 0.99;
constexpr int kDefaultMaxIters = 1000; // the forms without maxIters
// The inlier threshold is 1.96 sigma (Params::threshold), so a drop-in threshold implies sigma.
constexpr double kThresholdPerSigma = 1.959963984540054;

bool isRcmeMethod(int method)
{
    return method >= METHOD_RCME && method <= METHOD_COV_RANSAC;
}

// USAC_DEFAULT .. USAC_MAGSAC: the flags OpenCV hands to its USAC framework.
bool isUsacFlag(int method)
{
    return method >= USAC_DEFAULT && method <= USAC_MAGSAC;
}

/* OpenCV's classic flags and their combinations: calib3d decodes any value outside USAC_* by its
bits (findFundamentalMat: exactly FM_8POINT is the direct 8-point solution, `(method & ~3) ==
FM_RANSAC` RANSAC, the rest LMedS; findEssentialMat: exactly RANSAC is RANSAC, the rest LMedS),
so FM_RANSAC | FM_8POINT (10) runs RANSAC and FM_LMEDS | FM_8POINT (6) LMedS there. Every
combination of the four FM_* bits and RHO are accepted here; other values (99, negative) are
rejected, naming `method`, where OpenCV would silently run LMedS. */
bool isClassicFlag(int method)
{
    return (method >= 0 && method <= (FM_7POINT | FM_8POINT | FM_LMEDS | FM_RANSAC)) ||
           method == RHO;
}

// OpenCV's method flags, mapped to the rcme method of the same intent (doc/dropin.md). Every
// robust flag (RANSAC, LMedS and their combinations, RHO) is METHOD_STANDARD; exactly FM_7POINT or
// FM_8POINT pick that solver.
void applyMethodFlag(int method, Params& p)
{
    if (isRcmeMethod(method)) {
        p.method = static_cast<Method>(method);
        return;
    }
    p.method = METHOD_STANDARD;
    switch (method) {
    case FM_7POINT:
        p.solver = SOLVER_SEVEN_POINT;
        return;
    case FM_8POINT:
    case USAC_FM_8PTS:
        p.solver = SOLVER_EIGHT_POINT;
        return;
    case USAC_DEFAULT:
    case USAC_FAST:
        return;
    case USAC_PARALLEL:
        p.isParallel = true;
        return;
    case USAC_ACCURATE:
        p.localOptimization = true;
        return;
    case USAC_PROSAC: // points sorted by quality, as OpenCV assumes
        p.sampler = SAMPLER_PROSAC;
        return;
    case USAC_MAGSAC: // a threshold-robust likelihood score
        p.method = METHOD_MLESAC;
        return;
    default:
        break;
    }
    if (isClassicFlag(method))
        return;
    CV_Error(Error::StsBadArg,
             cv::format("method: %d is neither an OpenCV method flag (FM_* and their "
                        "combinations, LMEDS, RANSAC, RHO, USAC_*) nor a cv::rcme::Method value",
                        method));
}

void setThreshold(double threshold, double fallback, Params& p)
{
    p.threshold = (threshold > 0 && std::isfinite(threshold)) ? threshold : fallback;
    p.sigma = p.threshold / kThresholdPerSigma; // for the methods that model the noise
}

Params dropInParams(int method, double threshold, double fallbackThreshold, int maxIters)
{
    Params p;
    applyMethodFlag(method, p);
    setThreshold(threshold, fallbackThreshold, p);
    p.maxIterations = std::min(std::max(maxIters, 1), detail::kMaxIterationsLimit); // OpenCV: >= 1
    return p;
}

// findFundamentalMat replaces a confidence outside (0, 1) by 0.99; only NaN fails there.
Params fundamentalParams(int method, double threshold, double confidence, int maxIters)
{
    if (std::isnan(confidence))
        CV_Error(Error::StsBadArg, "confidence must be a number in (0, 1)");
    Params p = dropInParams(method, threshold, kFundamentalDefaultThreshold, maxIters);
    p.confidence = (confidence > DBL_EPSILON && confidence < 1 - DBL_EPSILON) ? confidence
                                                                              : kDefaultConfidence;
    return p;
}

// OpenCV estimates E with the 5-point solver (RANSAC, LMedS, every classic flag, USAC alike), and
// so does rcme's drop-in, unless the flag is USAC_FM_8PTS or the method is rcme's own (its
// defaults apply). On KITTI 06 with ORB matches the 8-point E of METHOD_STANDARD was 5 to 7
// degrees off on two of four pairs where the 5-point one was within 1 degree (doc/results.md).
void useFivePointSolverForEssential(int method, Params& p)
{
    if (!isRcmeMethod(method) && method != USAC_FM_8PTS)
        p.solver = SOLVER_FIVE_POINT;
}

// findEssentialMat rejects a confidence outside (0, 1).
Params essentialParams(int method, double prob, double threshold, int maxIters)
{
    if (!(prob > 0 && prob < 1))
        CV_Error(Error::StsBadArg, cv::format("prob must be in (0, 1), got %g", prob));
    Params p = dropInParams(method, threshold, kEssentialDefaultThreshold, maxIters);
    p.confidence = prob;
    useFivePointSolverForEssential(method, p);
    return p;
}

// The UsacParams fields rcme has, read as OpenCV's USAC reads them (it accepts any confidence,
// count and threshold); NAPSAC's neighbourhood sampling has no counterpart, uniform sampling has
// the same intent.
Params usacParams(const UsacParams& usac)
{
    UsacParams shared = usac;
    if (shared.sampler == SAMPLING_NAPSAC || shared.sampler == SAMPLING_PROGRESSIVE_NAPSAC)
        shared.sampler = SAMPLING_UNIFORM;
    Params p(shared);
    if (usac.score == SCORE_METHOD_MAGSAC)
        p.method = METHOD_MLESAC;
    if (!(p.confidence > 0 && p.confidence < 1))
        p.confidence = kDefaultConfidence;
    p.maxIterations = std::min(std::max(p.maxIterations, 1), detail::kMaxIterationsLimit);
    setThreshold(usac.threshold, kUsacDefaultThreshold, p);
    return p;
}

// findFundamentalMat also takes homogeneous points (Nx3, or 3 channels), as OpenCV does.
Mat euclideanPoints(InputArray points)
{
    Mat m = points.getMat();
    if (!m.empty() && m.checkVector(2, -1, false) < 0 && m.checkVector(3, -1, false) > 0) {
        Mat euclidean;
        convertPointsFromHomogeneous(m, euclidean);
        return euclidean;
    }
    return m;
}

/* The points as OpenCV's USAC reads them (the USAC_* flags and the UsacParams forms): one point
per row or per column, whichever side is longer, with its coordinates in the channels or along
the shorter side, so a 2xN single-channel matrix too; homogeneous points as above. What is left
malformed (a single point, one coordinate) readPoints rejects, naming the argument. */
Mat usacLayoutPoints(InputArray points)
{
    Mat m = points.getMat();
    if (m.empty() || m.dims > 2)
        return m;
    if (m.channels() > 1)
        m = (m.isContinuous() ? m : m.clone()).reshape(1, static_cast<int>(m.total()));
    if (m.rows < m.cols)
        m = m.t();
    if (m.cols == 3)
        return euclideanPoints(m);
    return m.cols > 3 ? m.colRange(0, 2) : m;
}

/* The points of the two-camera forms, which OpenCV passes to cv::undistortPoints first: CV_32F or
CV_64F, continuous, Nx2 or 2xN with one channel, Nx1 or 1xN with two. */
Mat undistortLayoutPoints(InputArray points, const char* name)
{
    Mat m = points.getMat();
    if (m.empty())
        return m;
    if (m.depth() != CV_32F && m.depth() != CV_64F)
        CV_Error(Error::StsBadArg,
                 cv::format("%s must be CV_32F or CV_64F in the two-camera forms (they undistort "
                            "with cv::undistortPoints, as OpenCV's), got depth %d",
                            name, m.depth()));
    if (m.checkVector(2) < 0 && m.dims == 2)
        m = m.t();
    if (m.checkVector(2) < 0)
        CV_Error(Error::StsBadArg, cv::format("%s must be a continuous Nx2 or 2xN (1 channel), "
                                              "Nx1 or 1xN (2 channels) array",
                                              name));
    return m;
}

// OpenCV's findEssentialMat and recoverPose require both point sets of one type once converted
// to CV_64F: the same number of channels.
void requireSameLayout(InputArray points1, InputArray points2)
{
    if (!points1.empty() && !points2.empty() && points1.channels() != points2.channels())
        CV_Error(Error::StsUnmatchedSizes,
                 cv::format("points1 and points2 must have the same layout (%d vs %d channels)",
                            points1.channels(), points2.channels()));
}

/* OpenCV's mask output, written into the caller's buffer where OpenCV writes it: calib3d's RANSAC
and LMedS (`allowTransposed`) keep a continuous 1xN or an Nx1 CV_8U array, USAC and recoverPose
an Nx1 one; anything else is replaced by a new Nx1 CV_8U array. */
void writeOpenCVMask(const Mat& values, OutputArray mask, bool allowTransposed)
{
    if (!mask.needed())
        return;
    const int n = static_cast<int>(values.total());
    mask.create(n, 1, CV_8U, -1, allowTransposed);
    Mat out = mask.getMat();
    const Mat column = values.reshape(1, n);
    (out.rows == n ? column : column.reshape(1, 1)).copyTo(out);
}

// OpenCV's scale of F: F(2,2) = 1 where it is not (nearly) zero; rcme's F has unit norm. Each
// 3x3 block of a stack of solutions is scaled so.
Mat fundamentalInOpenCVScale(const Mat& F)
{
    Mat scaled = F.clone();
    for (int r = 0; r + 3 <= scaled.rows; r += 3) {
        Mat block = scaled.rowRange(r, r + 3);
        if (std::abs(block.at<double>(2, 2)) > FLT_EPSILON)
            block /= block.at<double>(2, 2);
    }
    return scaled;
}

// OpenCV's scale of E: unit Frobenius norm (singular values 1/sqrt(2), 1/sqrt(2), 0), per block.
Mat essentialInOpenCVScale(const Mat& E)
{
    Mat scaled = E.clone();
    for (int r = 0; r + 3 <= scaled.rows; r += 3) {
        Mat block = scaled.rowRange(r, r + 3);
        block /= norm(block);
    }
    return scaled;
}

/* The model of few points that all agree with it (drop_in/agreeing_points.hpp), where the
estimate refused for want of evidence (no support beyond chance, not enough points for its solver,
an undetermined motion); a degenerate configuration or a pure rotation is evidence and stays
refused. */
void answerAgreeingPoints(const detail::TwoViewData& data, Status status, bool stackSolutions,
                          Mat& model)
{
    if (model.empty() && data.size() < detail::kDropInFewPoints &&
        (status == STATUS_POOR_QUALITY_INPUT || status == STATUS_NOT_ENOUGH_POINTS ||
         status == STATUS_UNDETERMINED_MOTION))
        model = detail::modelOfAgreeingPoints(data, stackSolutions);
}

/* The drop-in's answer in OpenCV's terms: the model, found by the estimate or agreed by few points,
and the mask of the points within the threshold of it by the distance of the OpenCV estimator the
form stands for (drop_in/opencv_inlier_mask.hpp), or zeros without a model. `classic`: a form
OpenCV runs outside USAC (its RANSAC and LMedS: stacked minimal solutions, a 1xN mask buffer
kept). */
Mat answerAsOpenCV(InputArray points1, InputArray points2, InputArray cameraMatrix,
                   const Params& params, bool classic, OutputArray mask)
{
    const Report report = estimateRelativeMotion(points1, points2, cameraMatrix, params);
    const detail::TwoViewData data =
        detail::makeTwoViewData(points1, points2, cameraMatrix, params);
    Mat model = data.calibrated ? report.E : report.F;
    answerAgreeingPoints(data, report.status, classic, model);
    using Distance = detail::OpenCVInlierDistance;
    const Distance distance =
        data.calibrated ? (classic ? Distance::Sampson : Distance::SymmetricEpipolarDistance)
                        : (classic ? Distance::LargerEpipolarLineDistance : Distance::Sampson);
    writeOpenCVMask(model.empty() ? Mat(data.size(), 1, CV_8U, Scalar(0))
                                  : detail::opencvInlierMask(data, model, distance),
                    mask, classic);
    return data.calibrated ? essentialInOpenCVScale(model) : fundamentalInOpenCVScale(model);
}

Mat cameraMatrixFromFocal(double focal, Point2d pp)
{
    Mat K;
    eigen2cv(detail::cameraMatrixFromFocal(focal, pp), K);
    return K;
}

/* The two-camera forms, as OpenCV computes them: both views undistorted, then mapped back to
pixels by the mean of the two camera matrices, which becomes the camera matrix of the estimate;
so the threshold keeps its meaning in pixels. Returns that mean matrix. The points' layouts are
those of cv::undistortPoints, or with `usacLayout` and no distortion USAC's, as OpenCV reads them.
*/
Mat undistortToMeanCamera(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                          InputArray distCoeffs1, InputArray cameraMatrix2, InputArray distCoeffs2,
                          bool usacLayout, Mat& undistorted1, Mat& undistorted2)
{
    const bool usacReading = usacLayout && distCoeffs1.empty() && distCoeffs2.empty();
    Eigen::Matrix3d K1, K2;
    if (!detail::readCameraMatrix(cameraMatrix1, "cameraMatrix1", K1))
        CV_Error(Error::StsBadArg, "cameraMatrix1 is required");
    if (!detail::readCameraMatrix(cameraMatrix2, "cameraMatrix2", K2))
        CV_Error(Error::StsBadArg, "cameraMatrix2 is required");
    Mat K1m, K2m, K0;
    eigen2cv(K1, K1m);
    eigen2cv(K2, K2m);
    eigen2cv(Eigen::Matrix3d((K1 + K2) / 2), K0);
    const auto undistort = [&](InputArray points, const char* name, const Mat& K,
                               InputArray distortion, Mat& out) {
        std::vector<Point2d> xy;
        const Mat laidOut =
            usacReading ? usacLayoutPoints(points) : undistortLayoutPoints(points, name);
        for (const Eigen::Vector2d& x : detail::readPoints(laidOut, name))
            xy.emplace_back(x.x(), x.y());
        undistortPoints(xy, out, K, distortion, noArray(), K0);
    };
    undistort(points1, "points1", K1m, distCoeffs1, undistorted1);
    undistort(points2, "points2", K2m, distCoeffs2, undistorted2);
    if (undistorted1.total() != undistorted2.total())
        CV_Error(Error::StsUnmatchedSizes,
                 "points1 and points2 must hold the same number of points");
    return K0;
}

void writeZeroMask(int n, OutputArray mask)
{
    if (mask.needed())
        detail::writeMask(std::vector<uchar>(static_cast<size_t>(n), 0), mask);
}

// What recoverPose gives when there is no motion: a standing camera that no point supports.
void writeStandingCamera(OutputArray R, OutputArray t)
{
    Mat(Mat::eye(3, 3, CV_64F)).copyTo(R);
    Mat(Mat::zeros(3, 1, CV_64F)).copyTo(t);
}

// findFundamentalMat's answer in OpenCV's terms: F in its scale, or an empty F with a zero mask.
Mat fundamentalDropIn(const Mat& points1, const Mat& points2, const Params& params, bool classic,
                      OutputArray mask)
{
    return answerAsOpenCV(points1, points2, noArray(), params, classic, mask);
}

// findEssentialMat's answer in OpenCV's terms: E in its scale, or an empty E with a zero mask.
// (The status form keeps a pure rotation's inliers beside its empty E; here no E means no
// inliers.)
Mat essentialDropIn(InputArray points1, InputArray points2, InputArray cameraMatrix,
                    const Params& params, bool classic, OutputArray mask)
{
    if (cameraMatrix.empty())
        CV_Error(Error::StsBadArg, "cameraMatrix is required (use findFundamentalMat without it)");
    return answerAsOpenCV(points1, points2, cameraMatrix, params, classic, mask);
}

// The selection recoverPose's mask argument makes on input: all points when it is empty.
std::vector<uchar> readSelection(InputOutputArray mask, size_t n)
{
    std::vector<uchar> selection(n, 1);
    if (mask.empty())
        return selection;
    const Mat m = mask.getMat();
    if (m.total() != n || m.channels() != 1 || m.depth() != CV_8U)
        CV_Error(Error::StsBadArg, "mask must be empty or an N-element CV_8U array");
    const Mat flat = m.isContinuous() ? m : m.clone();
    for (size_t i = 0; i < n; ++i)
        selection[i] = flat.ptr<uchar>()[i] != 0;
    return selection;
}

// recoverPose from a known E. An empty or zero E (what findEssentialMat returns when it finds
// nothing) is answered with a standing camera and no point, where cv::recoverPose throws.
int poseFromEssential(InputArray E, InputArray points1, InputArray points2, InputArray cameraMatrix,
                      OutputArray R, OutputArray t, double distanceThresh, InputOutputArray mask,
                      OutputArray triangulatedPoints)
{
    requireSameLayout(points1, points2);
    const std::vector<Eigen::Vector2d> p1 = detail::readPoints(points1, "points1");
    const std::vector<Eigen::Vector2d> p2 = detail::readPoints(points2, "points2");
    if (p1.size() != p2.size())
        CV_Error(Error::StsUnmatchedSizes,
                 "points1 and points2 must hold the same number of points");
    Eigen::Matrix3d K;
    if (!detail::readCameraMatrix(cameraMatrix, "cameraMatrix", K))
        CV_Error(Error::StsBadArg, "cameraMatrix is required");
    std::vector<uchar> selection = readSelection(mask, p1.size());

    Mat e64;
    if (!E.empty()) {
        const Mat e = E.getMat();
        if (e.rows != 3 || e.cols != 3 || e.channels() != 1)
            CV_Error(Error::StsBadArg,
                     cv::format("E must be a 3x3 matrix with one channel (or empty), got %dx%d "
                                "with %d channels",
                                e.rows, e.cols, e.channels()));
        e.convertTo(e64, CV_64F);
        if (!checkRange(e64))
            CV_Error(Error::StsBadArg, "E has a non-finite entry");
    }
    const int n = static_cast<int>(p1.size());
    if (e64.empty() || norm(e64) == 0) {
        writeStandingCamera(R, t);
        writeZeroMask(n, mask);
        triangulatedPoints.release();
        return 0;
    }
    Eigen::Matrix3d essential;
    cv2eigen(e64, essential);
    Eigen::Matrix3d rotation;
    Eigen::Vector3d translation;
    const Eigen::Matrix3d Kinv = K.inverse();
    detail::recoverMotionFromEssential(essential, p1, p2, Kinv, &selection, rotation, translation,
                                       distanceThresh);
    std::vector<uchar> inFront;
    const int count = detail::countPointsInFront(rotation, translation, p1, p2, Kinv, &selection,
                                                 &inFront, distanceThresh);
    Mat Rm, tm;
    eigen2cv(rotation, Rm);
    eigen2cv(Eigen::Matrix<double, 3, 1>(translation), tm);
    Rm.copyTo(R);
    tm.copyTo(t);
    if (mask.needed())
        detail::writeMask(inFront, mask);
    if (triangulatedPoints.needed()) {
        Mat normalized1(2, n, CV_64F), normalized2(2, n, CV_64F);
        for (int i = 0; i < n; ++i) {
            const Eigen::Vector3d x1 = Kinv * detail::homogeneous(p1[static_cast<size_t>(i)]);
            const Eigen::Vector3d x2 = Kinv * detail::homogeneous(p2[static_cast<size_t>(i)]);
            normalized1.at<double>(0, i) = x1.x() / x1.z();
            normalized1.at<double>(1, i) = x1.y() / x1.z();
            normalized2.at<double>(0, i) = x2.x() / x2.z();
            normalized2.at<double>(1, i) = x2.y() / x2.z();
        }
        Mat P2;
        hconcat(Rm, tm, P2);
        Mat points4D;
        triangulatePoints(Mat::eye(3, 4, CV_64F), P2, normalized1, normalized2, points4D);
        points4D.copyTo(triangulatedPoints);
    }
    return count;
}

} // namespace

Mat findFundamentalMat(InputArray points1, InputArray points2, int method,
                       double ransacReprojThreshold, double confidence, int maxIters,
                       OutputArray mask)
{
    const Params params = fundamentalParams(method, ransacReprojThreshold, confidence, maxIters);
    const bool usac = isUsacFlag(method);
    const auto read = [usac](InputArray points) {
        return usac ? usacLayoutPoints(points) : euclideanPoints(points);
    };
    return fundamentalDropIn(read(points1), read(points2), params, !usac, mask);
}

Mat findFundamentalMat(InputArray points1, InputArray points2, int method,
                       double ransacReprojThreshold, double confidence, OutputArray mask)
{
    return rcme::findFundamentalMat(points1, points2, method, ransacReprojThreshold, confidence,
                                    kDefaultMaxIters, mask);
}

Mat findFundamentalMat(InputArray points1, InputArray points2, OutputArray mask, int method,
                       double ransacReprojThreshold, double confidence)
{
    return rcme::findFundamentalMat(points1, points2, method, ransacReprojThreshold, confidence,
                                    kDefaultMaxIters, mask);
}

Mat findFundamentalMat(InputArray points1, InputArray points2, OutputArray mask,
                       const UsacParams& params)
{
    return fundamentalDropIn(usacLayoutPoints(points1), usacLayoutPoints(points2),
                             usacParams(params), false, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix, int method,
                     double prob, double threshold, int maxIters, OutputArray mask)
{
    // OpenCV's findEssentialMat hands USAC 1000 iterations, whatever maxIters says.
    const Params params =
        essentialParams(method, prob, threshold, isUsacFlag(method) ? kDefaultMaxIters : maxIters);
    if (isUsacFlag(method))
        return essentialDropIn(usacLayoutPoints(points1), usacLayoutPoints(points2), cameraMatrix,
                               params, false, mask);
    requireSameLayout(points1, points2);
    return essentialDropIn(points1, points2, cameraMatrix, params, true, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix, int method,
                     double prob, double threshold, OutputArray mask)
{
    return rcme::findEssentialMat(points1, points2, cameraMatrix, method, prob, threshold,
                                  kDefaultMaxIters, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, double focal, Point2d pp, int method,
                     double prob, double threshold, int maxIters, OutputArray mask)
{
    return rcme::findEssentialMat(points1, points2, cameraMatrixFromFocal(focal, pp), method, prob,
                                  threshold, maxIters, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, double focal, Point2d pp, int method,
                     double prob, double threshold, OutputArray mask)
{
    return rcme::findEssentialMat(points1, points2, cameraMatrixFromFocal(focal, pp), method, prob,
                                  threshold, kDefaultMaxIters, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                     InputArray distCoeffs1, InputArray cameraMatrix2, InputArray distCoeffs2,
                     int method, double prob, double threshold, OutputArray mask)
{
    const Params params = essentialParams(method, prob, threshold, kDefaultMaxIters);
    Mat u1, u2;
    const Mat K0 = undistortToMeanCamera(points1, points2, cameraMatrix1, distCoeffs1,
                                         cameraMatrix2, distCoeffs2, false, u1, u2);
    return essentialDropIn(u1, u2, K0, params, !isUsacFlag(method), mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                     InputArray cameraMatrix2, InputArray dist_coeff1, InputArray dist_coeff2,
                     OutputArray mask, const UsacParams& params)
{
    Params p = usacParams(params);
    p.solver = SOLVER_FIVE_POINT;
    Mat u1, u2;
    const Mat K0 = undistortToMeanCamera(points1, points2, cameraMatrix1, dist_coeff1,
                                         cameraMatrix2, dist_coeff2, true, u1, u2);
    return essentialDropIn(u1, u2, K0, p, false, mask);
}

int recoverPose(InputArray points1, InputArray points2, InputArray cameraMatrix1,
                InputArray distCoeffs1, InputArray cameraMatrix2, InputArray distCoeffs2,
                OutputArray E, OutputArray R, OutputArray t, int method, double prob,
                double threshold, InputOutputArray mask)
{
    const Params params = essentialParams(method, prob, threshold, kDefaultMaxIters);
    Mat u1, u2;
    const Mat K0 = undistortToMeanCamera(points1, points2, cameraMatrix1, distCoeffs1,
                                         cameraMatrix2, distCoeffs2, false, u1, u2);
    Status status;
    Mat inliers, essential;
    const int count = rcme::recoverPose(u1, u2, K0, essential, R, t, params, inliers, status);
    if (E.needed()) {
        if (essential.empty())
            E.release();
        else
            essentialInOpenCVScale(essential).copyTo(E);
    }
    // A pure rotation keeps its R (t = 0) and inliers: the right motion of a camera that turns
    // on the spot, which OpenCV code can use as it is.
    if (status != STATUS_SUCCESS && status != STATUS_PURE_ROTATION)
        writeStandingCamera(R, t);
    writeOpenCVMask(inliers, mask, false);
    return count;
}

int recoverPose(InputArray E, InputArray points1, InputArray points2, InputArray cameraMatrix,
                OutputArray R, OutputArray t, InputOutputArray mask)
{
    // cv::recoverPose's distance limit on the triangulated points, in baselines.
    constexpr double kOpenCVDistanceThresh = 50.0;
    return poseFromEssential(E, points1, points2, cameraMatrix, R, t, kOpenCVDistanceThresh, mask,
                             noArray());
}

int recoverPose(InputArray E, InputArray points1, InputArray points2, OutputArray R, OutputArray t,
                double focal, Point2d pp, InputOutputArray mask)
{
    return rcme::recoverPose(E, points1, points2, cameraMatrixFromFocal(focal, pp), R, t, mask);
}

int recoverPose(InputArray E, InputArray points1, InputArray points2, InputArray cameraMatrix,
                OutputArray R, OutputArray t, double distanceThresh, InputOutputArray mask,
                OutputArray triangulatedPoints)
{
    return poseFromEssential(E, points1, points2, cameraMatrix, R, t, distanceThresh, mask,
                             triangulatedPoints);
}

} // namespace rcme
} // namespace cv
