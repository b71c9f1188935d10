// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The public functions: each validates its arguments, runs one estimation and writes its outputs
// in OpenCV's conventions (CV_64F matrices, Nx1 CV_8U mask always written).

#include "precomp.hpp"

#include "framework/estimation_pipeline.hpp"
#include "framework/estimator_factory.hpp"
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

// What the estimate holds: F, and its motion when the model space made one (with K).
void setEstimate(Report& report, const detail::Model& model)
{
    report.F = toMat(model.F);
    if (model.motion()) {
        report.E = toMat(model.essential());
        report.R = toMat(model.motion()->R);
        report.t = toMat(model.motion()->t);
        if (const auto* uncertainty = model.uncertainty.as<detail::MotionUncertainty>())
            setMotionUncertainty(uncertainty->covariance, report);
    }
    report.noiseSigma = model.noiseSigma;
}

// The model a failed estimation rejected, for diagnostics only (Report::rejectedF...).
void setRejected(Report& report, const detail::Model& model)
{
    if (!model.F.allFinite() || model.F.isZero())
        return;
    report.rejectedF = toMat(model.F);
    if (model.motion()) {
        report.rejectedR = toMat(model.motion()->R);
        report.rejectedT = toMat(model.motion()->t);
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
    const detail::Estimation estimation = detail::estimateModel(data, components);
    const detail::Estimate& result = estimation.estimate;

    Estimation out;
    Report& report = out.report;
    out.mask = result.mask;
    out.inFront = result.inFront;
    report.status = result.status;
    report.message = result.message;
    if (result.status == STATUS_SUCCESS) {
        setEstimate(report, result.model);
    } else if (result.status == STATUS_PURE_ROTATION && result.rotation) {
        // R only: the translation is not determined, reported as zero; F and E stay empty.
        report.R = toMat(result.rotation->R);
        report.t = Mat::zeros(3, 1, CV_64F);
        if (result.rotation->covariance)
            report.covariance = toMat(*result.rotation->covariance);
    }
    if (result.status != STATUS_SUCCESS && result.hasRejected)
        setRejected(report, result.rejected);
    report.iterations = estimation.search.iterations;
    report.pointsPerHypothesis = estimation.search.pointsPerHypothesis;
    report.meanEntropy = result.score.meanEntropy;
    report.rivalCostGap = result.rivalCostGap;
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
