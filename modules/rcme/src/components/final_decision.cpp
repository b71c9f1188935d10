// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The last stage: the model space's last decision on the final estimate (ModelSpace::finish;
// with K, recoverPose's mask of the inliers in front of both cameras), also after a failure.

#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class FinalDecision final : public EstimationStage
{
public:
    bool runsOnFailure() const override { return true; }

    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        return context.space.finish(context.data, estimate);
    }
};

} // namespace

std::unique_ptr<EstimationStage> createFinalDecision()
{
    return std::make_unique<FinalDecision>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
