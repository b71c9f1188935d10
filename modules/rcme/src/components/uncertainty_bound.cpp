// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The uncertainty bound (Params::maxRotationStdDeg, maxTranslationStdDeg; calibrated data): a
// motion whose propagated standard deviation of a rotation axis, or of the translation direction,
// exceeds its bound is not determined to the asked accuracy: STATUS_UNDETERMINED_MOTION. It reads
// the final covariance (Params::refine).

#include "framework/component_factories.hpp"
#include "geometry/motion_parameterization.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class UncertaintyBound final : public EstimationStage
{
public:
    // A bound <= 0 is off.
    UncertaintyBound(double maxRotationStdDeg, double maxTranslationStdDeg)
        : maxRotationStdDeg_(maxRotationStdDeg), maxTranslationStdDeg_(maxTranslationStdDeg)
    {
    }

    StageOutcome run(const StageContext&, const Estimate& estimate) override
    {
        const Model& model = estimate.model;
        const MotionUncertainty* uncertainty = model.uncertainty.as<MotionUncertainty>();
        if (!uncertainty)
            return {};
        const Eigen::Matrix<double, 5, 5>& covariance = uncertainty->covariance;
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
