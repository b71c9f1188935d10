// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The uncertainty bound (Params::maxRotationStdDeg, maxTranslationStdDeg; calibrated data): a
// motion whose propagated standard deviation of a rotation axis, or of the translation direction,
// exceeds its bound is not determined to the asked accuracy: STATUS_UNDETERMINED_MOTION. It reads
// the final covariance (Params::refine), at the noise the final fit took: the estimate from 30
// residual degrees of freedom on, the stated sigma below. Below 30 the stated sigma is kept unless
// the residuals rule it out: then the noise read is the largest they do not rule out.

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* One-sided level at which the inliers' residuals rule out the stated sigma. Below 30 residual
degrees of freedom the estimate s is too noisy to replace the stated sigma (kMinNoiseDof), but it
still bounds the noise: nu s^2 / sigma^2 is chi-square with nu degrees of freedom, so a sigma above
s sqrt(nu / chi2_nu(0.01)) gives residuals as small as these in fewer than 1 % of the pairs. Reading
the stated sigma where the residuals exclude it flags motions the inliers do determine: templeSR
11-14 at 21 inliers, 0.23 px measured, rotation deviation 6.5 deg at 1 px and 2.1 deg at the
bound's 0.37 px; the motion's error 1.6 deg (doc/results.md). */
constexpr double kStatedNoiseExcludedAt = 0.01;

// The factor on the final covariance that takes it from the fit's noise to the largest noise the
// residuals do not rule out, when that is below the stated sigma; 1 otherwise.
double noiseTheResidualsAllow(const TwoViewData& data, const Model& model, int inliers)
{
    const int dof = inliers - MotionTangent::kDof;
    if (!data.useEstimatedNoise || dof < 1 || usesEstimatedNoise(data, model.noiseSigma, dof) ||
        !std::isfinite(model.noiseSigma))
        return 1.0;
    const double largest =
        model.noiseSigma * std::sqrt(dof / chiSquareQuantile(kStatedNoiseExcludedAt, dof));
    if (!(largest < data.sigma))
        return 1.0;
    return truncatedNoiseVariance(largest * largest, data.threshold) /
           truncatedNoiseVariance(data.sigma * data.sigma, data.threshold);
}

class UncertaintyBound final : public EstimationStage
{
public:
    // A bound <= 0 is off.
    UncertaintyBound(double maxRotationStdDeg, double maxTranslationStdDeg)
        : maxRotationStdDeg_(maxRotationStdDeg), maxTranslationStdDeg_(maxTranslationStdDeg)
    {
    }

    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const Model& model = estimate.model;
        const MotionUncertainty* uncertainty = model.uncertainty.as<MotionUncertainty>();
        if (!uncertainty)
            return {};
        const int inliers = static_cast<int>(
            std::count(estimate.mask.begin(), estimate.mask.end(), static_cast<uchar>(1)));
        const Eigen::Matrix<double, 5, 5> covariance =
            uncertainty->covariance * noiseTheResidualsAllow(context.data, model, inliers);
        const struct
        {
            const char* what;
            double stdDeg;
            const char* field;
            double bound;
        } checks[] = {
            {"rotation", rotationStdDeg(covariance).maxCoeff(), "maxRotationStdDeg",
             maxRotationStdDeg_},
            {"translation direction", translationDirectionStdDeg(covariance),
             "maxTranslationStdDeg", maxTranslationStdDeg_},
        };
        for (const auto& check : checks)
            if (check.bound > 0 && check.stdDeg > check.bound)
                return StageOutcome::rejecting(
                    STATUS_UNDETERMINED_MOTION,
                    cv::format("the %s's standard deviation %.2f deg exceeds Params.%s %.2f: the "
                               "motion is not determined",
                               check.what, check.stdDeg, check.field, check.bound),
                    model);
        return {};
    }

private:
    double maxRotationStdDeg_, maxTranslationStdDeg_;
};

} // namespace

std::unique_ptr<EstimationStage> createUncertaintyBound(double maxRotationStdDeg,
                                                        double maxTranslationStdDeg)
{
    return std::make_unique<UncertaintyBound>(maxRotationStdDeg, maxTranslationStdDeg);
}

} // namespace detail
} // namespace rcme
} // namespace cv
