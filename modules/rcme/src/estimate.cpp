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

// The covariance and its per-axis standard deviations in degrees.
void setMotionUncertainty(const Eigen::Matrix<double, 5, 5>& covariance, Report& report)
{
    report.covariance = toMat(covariance);
    report.rotationStdDeg = toMat(detail::rotationStdDeg(covariance));
    report.translationStdDeg = detail::translationDirectionStdDeg(covariance);
}

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
    if (params.timeBudget > 0)
        components.deadline =
            start + static_cast<int64>(std::min(params.timeBudget, 1e9) * getTickFrequency());
    detail::RansacResult result = detail::runRansac(data, components);
    if (params.degeneracyTest)
        detail::decideDegeneracy(data, components, result);
    detail::finalizeModel(data, components, result);
    detail::resolveRivalMotions(data, components, result);
    detail::checkMotionUncertainty(data, components, result);

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
                    setMotionUncertainty(model.covariance.topLeftCorner<5, 5>(), report);
            }
        } else {
            report.F = toMat(model.F);
        }
        if (report.status == STATUS_SUCCESS)
            report.noiseSigma = model.noiseSigma;
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
    report.rivalCostGap = result.rivalCostGap;
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

Mat findEssentialMat(InputArray points1, InputArray points2, InputArray cameraMatrix,
                     const Params& params, OutputArray mask, Status& status)
{
    requireCameraMatrix(cameraMatrix);
    const Estimation e = estimate(points1, points2, cameraMatrix, params);
    status = e.report.status;
    detail::writeMask(e.mask, mask);
    return e.report.E;
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

} // namespace rcme
} // namespace cv
