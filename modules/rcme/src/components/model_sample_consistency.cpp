// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 1(b) of Fig. 1(b), the model-sample consistency test (paper eq. 2-3): every sample must fit
// the model it built, d_k^2 / v_k <= F_dof^-1(1 - alpha), with v_k the variance of its Sampson
// distance propagated from the noise and the model's covariance. Meaningful only for
// over-parameterized solvers (an exact solver fits its sample by construction).

#include "components/residual_uncertainty.hpp"
#include "framework/component_factories.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class ModelSampleConsistencyTest final : public ModelVerifier
{
public:
    ModelSampleConsistencyTest(const TwoViewData& data, bool leverage)
        : sigma_(data.sigma), bound_(data.consistencyBound), leverage_(leverage)
    {
    }

    bool isModelGood(const TwoViewData& data, const std::vector<int>& sample, Model& model) override
    {
        if (!model.uncertainty.isKnown())
            return false;
        const ResidualUncertainty uncertainty(model, sigma_);
        for (int i : sample) {
            double distanceSquared = 0, variance = 0;
            uncertainty.evaluate(data.points1[static_cast<size_t>(i)],
                                 data.points2[static_cast<size_t>(i)], leverage_, distanceSquared,
                                 variance);
            if (!(distanceSquared <= bound_ * variance))
                return false;
        }
        return true;
    }

    std::unique_ptr<ModelVerifier> clone() const override
    {
        return std::make_unique<ModelSampleConsistencyTest>(*this);
    }

private:
    double sigma_;
    double bound_;
    bool leverage_;
};

} // namespace

std::unique_ptr<ModelVerifier> createModelSampleConsistencyTest(const TwoViewData& data,
                                                                bool leverage)
{
    return std::make_unique<ModelSampleConsistencyTest>(data, leverage);
}

} // namespace detail
} // namespace rcme
} // namespace cv
