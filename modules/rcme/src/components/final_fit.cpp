// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The estimate's final fit and covariance (framework/refinement.cpp, Refiner::finalize), once
// what the inliers determine is decided (the homography comparison): the model it fits is the
// one that is returned.

#include "framework/component_factories.hpp"
#include "framework/refinement.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class FinalFit final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        StageOutcome outcome;
        Model& model = outcome.model.emplace(estimate.model);
        std::vector<uchar>& inliers = outcome.inliers.emplace(estimate.mask);
        context.refinement.finalFit(context.data, model, inliers);
        return outcome;
    }
};

} // namespace

std::unique_ptr<EstimationStage> createFinalFit()
{
    return std::make_unique<FinalFit>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
