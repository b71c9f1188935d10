// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The public functions: each validates its arguments, runs one estimation and writes its outputs
// in OpenCV's conventions (CV_64F matrices, Nx1 CV_8U mask always written).

#include "precomp.hpp"

#include "framework/estimator_factory.hpp"
#include "framework/ransac_loop.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"

#include <opencv2/core/eigen.hpp>

namespace cv {
namespace rcme {

namespace {

template <typename Derived> Mat toMat(const Eigen::MatrixBase<Derived>& m)
{
    Mat out;
    eigen2cv(Eigen::Matrix<double, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime>(m), out);
    return out;
}

// The estimate with its cheirality mask (calibrated case), shared by every public entry point.
struct Estimation
{
    Report report;
    std::vector<uchar> mask;    //!< inliers
    std::vector<uchar> inFront; //!< inliers in front of both cameras (calibrated only)
};

void fail(Report& report, std::vector<uchar>& mask, Status status, const std::string& message)
{
    report = Report();
    report.status = status;
    report.message = message;
    std::fill(mask.begin(), mask.end(), 0);
}

// The model a failed estimation rejected, for diagnostics only (Report::rejectedF...).
void setRejected(Report& report, const detail::Model& model, bool calibrated)
{
    if (!model.F.allFinite() || model.F.isZero())
        return;
    report.rejectedF = toMat(model.F);
    if (calibrated && model.hasMotion) {
        report.rejectedR = toMat(model.R);
        report.rejectedT = toMat(model.t);
    }
}

Estimation estimate(InputArray points1, InputArray points2, InputArray cameraMatrix,
                    const Params& params)
{
    const int64 start = getTickCount();
    const detail::TwoViewData data =
        detail::makeTwoViewData(points1, points2, cameraMatrix, params);
    detail::EstimatorComponents components = detail::createEstimator(params, data);
    detail::RansacResult result = detail::runRansac(data, components);
    if (params.degeneracyTest)
        detail::decideDegeneracy(data, components, result);

    Estimation out;
    Report& report = out.report;
    out.mask = result.mask;
    report.status = result.status;
    report.message = result.message;
    if (result.status == STATUS_SUCCESS) {
        detail::Model& model = result.model;
        if (data.calibrated) {
            // The loop gives every calibrated estimate its motion.
            CV_Assert(model.hasMotion);
            if (detail::countPointsInFront(model.R, model.t, data.points1, data.points2, data.Kinv,
                                           &out.mask, &out.inFront) == 0) {
                fail(report, out.mask, STATUS_DEGENERATE_CONFIGURATION,
                     "no decomposition of E puts the inliers in front of both cameras");
                setRejected(report, model, data.calibrated);
            } else {
                report.F = toMat(model.F);
                report.E = toMat(detail::skew(model.t) * model.R);
                report.R = toMat(model.R);
                report.t = toMat(model.t);
                if (model.uncertaintyDof == detail::MotionTangent::kDof)
                    report.covariance = toMat(model.covariance.topLeftCorner<5, 5>());
            }
        } else {
            report.F = toMat(model.F);
        }
    } else if (result.status == STATUS_PURE_ROTATION) {
        // R only: the translation is not determined, reported as zero; F and E stay empty.
        report.R = toMat(result.model.R);
        report.t = Mat::zeros(3, 1, CV_64F);
        if (result.model.uncertaintyDof == 3)
            report.covariance = toMat(result.model.covariance.topLeftCorner<3, 3>());
        out.inFront = out.mask;
    }
    if (result.status != STATUS_SUCCESS && result.hasRejected)
        setRejected(report, result.rejected, data.calibrated);
    report.iterations = result.iterations;
    report.pointsPerHypothesis = result.pointsPerHypothesis;
    report.meanEntropy = result.score.meanEntropy;
    if (report.status != STATUS_SUCCESS && report.status != STATUS_PURE_ROTATION)
        out.inFront.assign(out.mask.size(), 0);
    report.inlierCount = static_cast<int>(std::count(out.mask.begin(), out.mask.end(), 1));
    report.mask = Mat(static_cast<int>(out.mask.size()), 1, CV_8U, out.mask.data()).clone();
    report.timeSeconds = static_cast<double>(getTickCount() - start) / getTickFrequency();
    return out;
}

void requireCameraMatrix(InputArray cameraMatrix)
{
    if (cameraMatrix.empty())
        CV_Error(Error::StsBadArg, "cameraMatrix is required (use findFundamentalMat without it)");
}

// OpenCV's flags select the Standard method; rcme's own Method values pass through.
Method methodFromFlag(int method)
{
    if (method == FM_RANSAC || method == RANSAC)
        return METHOD_STANDARD;
    if (method >= METHOD_RCME && method <= METHOD_COV_RANSAC)
        return static_cast<Method>(method);
    CV_Error(Error::StsBadArg,
             cv::format("method: %d is not supported by cv::rcme; use cv::FM_RANSAC / cv::RANSAC "
                        "or a cv::rcme::Method value",
                        method));
}

Params paramsFromDropIn(int method, double threshold, double confidence, int maxIters)
{
    Params params;
    params.method = methodFromFlag(method);
    params.threshold = threshold;
    // The noise level the threshold implies, for the methods that model it.
    if (threshold > 0 && std::isfinite(threshold))
        params.sigma = threshold / 1.959963984540054;
    params.confidence = confidence;
    params.maxIterations = maxIters;
    return params;
}

void writeOrRelease(const Mat& m, OutputArray out)
{
    if (!out.needed())
        return;
    if (m.empty())
        out.release();
    else
        m.copyTo(out);
}

} // namespace

Report estimateRelativeMotion(InputArray points1, InputArray points2, InputArray cameraMatrix,
                              const Params& params)
{
    return estimate(points1, points2, cameraMatrix, params).report;
}

Mat findFundamentalMat(InputArray points1, InputArray points2, const Params& params,
                       OutputArray mask, Status& status)
{
    return rcme::findFundamentalMat(points1, points2, noArray(), params, mask, status);
}

Mat findFundamentalMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                       const Params& params, OutputArray mask, Status& status)
{
    const Estimation e = estimate(points1, points2, cameraMatrix, params);
    status = e.report.status;
    detail::writeMask(e.mask, mask);
    return e.report.F;
}

Mat findFundamentalMat(InputArray points1, InputArray points2, int method,
                       double ransacReprojThreshold, double confidence, int maxIters,
                       OutputArray mask)
{
    Status status;
    return rcme::findFundamentalMat(
        points1, points2, paramsFromDropIn(method, ransacReprojThreshold, confidence, maxIters),
        mask, status);
}

Mat findFundamentalMat(InputArray points1, InputArray points2, int method,
                       double ransacReprojThreshold, double confidence, OutputArray mask)
{
    return rcme::findFundamentalMat(points1, points2, method, ransacReprojThreshold, confidence,
                                    1000, mask);
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                     const Params& params, OutputArray mask, Status& status)
{
    requireCameraMatrix(cameraMatrix);
    const Estimation e = estimate(points1, points2, cameraMatrix, params);
    status = e.report.status;
    detail::writeMask(e.mask, mask);
    return e.report.E;
}

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix, int method,
                     double prob, double threshold, int maxIters, OutputArray mask)
{
    Status status;
    return rcme::findEssentialMat(points1, points2, cameraMatrix,
                                  paramsFromDropIn(method, threshold, prob, maxIters), mask,
                                  status);
}

Mat findEssentialMat(InputArray points1, InputArray points2, double focal, Point2d pp, int method,
                     double prob, double threshold, int maxIters, OutputArray mask)
{
    Mat K;
    eigen2cv(detail::cameraMatrixFromFocal(focal, pp), K);
    return rcme::findEssentialMat(points1, points2, K, method, prob, threshold, maxIters, mask);
}

int recoverPose(InputArray points1, InputArray points2, InputArray cameraMatrix, OutputArray E,
                OutputArray R, OutputArray t, const Params& params, OutputArray mask,
                Status& status, OutputArray covariance)
{
    requireCameraMatrix(cameraMatrix);
    const Estimation e = estimate(points1, points2, cameraMatrix, params);
    status = e.report.status;
    writeOrRelease(e.report.E, E);
    writeOrRelease(e.report.R, R);
    writeOrRelease(e.report.t, t);
    writeOrRelease(e.report.covariance, covariance);
    detail::writeMask(e.inFront, mask);
    return static_cast<int>(std::count(e.inFront.begin(), e.inFront.end(), 1));
}

int recoverPose(InputArray E, InputArray points1, InputArray points2, InputArray cameraMatrix,
                OutputArray R, OutputArray t, InputOutputArray mask)
{
    const Mat e = E.getMat();
    if (e.rows != 3 || e.cols != 3 || e.channels() != 1 ||
        (e.depth() != CV_32F && e.depth() != CV_64F))
        CV_Error(Error::StsBadArg, "E must be a 3x3 CV_32F or CV_64F matrix");
    Mat e64;
    e.convertTo(e64, CV_64F);
    if (!checkRange(e64) || norm(e64) == 0)
        CV_Error(Error::StsBadArg, "E must be finite and non-zero");
    Eigen::Matrix3d essential;
    cv2eigen(e64, essential);

    const std::vector<Eigen::Vector2d> p1 = detail::readPoints(points1, "points1");
    const std::vector<Eigen::Vector2d> p2 = detail::readPoints(points2, "points2");
    if (p1.size() != p2.size())
        CV_Error(Error::StsUnmatchedSizes,
                 "points1 and points2 must hold the same number of points");
    Eigen::Matrix3d K;
    requireCameraMatrix(cameraMatrix);
    detail::readCameraMatrix(cameraMatrix, "cameraMatrix", K);

    std::vector<uchar> selection(p1.size(), 1);
    if (!mask.empty()) {
        const Mat m = mask.getMat();
        if (m.total() != p1.size() || m.channels() != 1 || m.depth() != CV_8U)
            CV_Error(Error::StsBadArg, "mask must be empty or an N-element CV_8U array");
        const Mat flat = m.isContinuous() ? m : m.clone();
        for (size_t i = 0; i < selection.size(); ++i)
            selection[i] = flat.ptr<uchar>()[i] != 0;
    }
    Eigen::Matrix3d rotation;
    Eigen::Vector3d translation;
    const Eigen::Matrix3d Kinv = K.inverse();
    detail::recoverMotionFromEssential(essential, p1, p2, Kinv, &selection, rotation, translation);
    std::vector<uchar> inFront;
    const int count =
        detail::countPointsInFront(rotation, translation, p1, p2, Kinv, &selection, &inFront);
    toMat(rotation).copyTo(R);
    toMat(translation).copyTo(t);
    if (mask.needed())
        detail::writeMask(inFront, mask);
    return count;
}

int recoverPose(InputArray E, InputArray points1, InputArray points2, OutputArray R, OutputArray t,
                double focal, Point2d pp, InputOutputArray mask)
{
    Mat K;
    eigen2cv(detail::cameraMatrixFromFocal(focal, pp), K);
    return rcme::recoverPose(E, points1, points2, K, R, t, mask);
}

} // namespace rcme
} // namespace cv
