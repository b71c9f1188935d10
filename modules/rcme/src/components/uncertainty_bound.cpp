// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The uncertainty bound (Params::maxRotationStdDeg, maxTranslationStdDeg; calibrated data): a
// motion whose propagated standard deviation of a rotation axis, or of the translation direction,
// exceeds its bound is not determined to the asked accuracy: STATUS_UNDETERMINED_MOTION. It reads
// the final covariance (Params::refine).

#include "framework/component_factories.hpp"
#include "framework/ransac_loop.hpp"
#include "geometry/motion_parameterization.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class UncertaintyBound : public EstimateTest
{
public:
    // A bound <= 0 is off.
    UncertaintyBound(double maxRotationStdDeg, double maxTranslationStdDeg)
        : maxRotationStdDeg_(maxRotationStdDeg), maxTranslationStdDeg_(maxTranslationStdDeg)
    {
    }

    void apply(const TwoViewData&, EstimatorComponents&, RansacResult& result) override
    {
        const Model& model = result.model;
        if (model.uncertaintyDof != MotionTangent::kDof)
            return;
        const Eigen::Matrix<double, 5, 5> covariance = model.covariance.topLeftCorner<5, 5>();
        const double rotationStd = rotationStdDeg(covariance).maxCoeff();
        const double translationStd = translationDirectionStdDeg(covariance);
        if (maxRotationStdDeg_ > 0 && rotationStd > maxRotationStdDeg_)
            rejectModel(result, STATUS_UNDETERMINED_MOTION,
                        cv::format("the rotation's standard deviation %.2f deg exceeds "
                                   "Params.maxRotationStdDeg %.2f: the motion is not determined",
                                   rotationStd, maxRotationStdDeg_),
                        model);
        else if (maxTranslationStdDeg_ > 0 && translationStd > maxTranslationStdDeg_)
            rejectModel(
                result, STATUS_UNDETERMINED_MOTION,
                cv::format("the translation direction's standard deviation %.2f deg exceeds "
                           "Params.maxTranslationStdDeg %.2f: the motion is not determined",
                           translationStd, maxTranslationStdDeg_),
                model);
    }

private:
    double maxRotationStdDeg_, maxTranslationStdDeg_;
};

} // namespace

std::unique_ptr<EstimateTest> createUncertaintyBound(double maxRotationStdDeg,
                                                    double maxTranslationStdDeg)
{
    return std::make_unique<UncertaintyBound>(maxRotationStdDeg, maxTranslationStdDeg);
}

} // namespace detail
} // namespace rcme
} // namespace cv
