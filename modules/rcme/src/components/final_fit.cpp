// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The estimate's final fit and covariance (framework/refinement.cpp, Refiner::finalize), once
// what the inliers determine is decided (the homography comparison): the model it fits is the
// one that is returned.
//
// The fit's rounds take the band again and drop the inliers the others do not confirm (high
// leverage). Where the outliers can have put a point into the band by chance (at least one
// expected: their count times chanceOfBand), that drops chance inliers far from the others, which
// pull F off where it is extrapolated. Where they cannot, it drops true matches: when two alone fix
// a direction of F, both go, and F moves off them to fewer points at a higher cost. So without K,
// where no stage after this one weighs F against another model, the fit is then kept only as a
// refinement is kept, when the scorer does not rate it worse than the F it started from
// (doc/f_only.md, "The final fit kept as a refinement"). With K the rival decisions after it refit
// and weigh the motions.

#include "framework/component_factories.hpp"
#include "framework/refinement.hpp"

#include <algorithm>

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
        if (context.data.calibrated || chanceInliersExpected(context.data, inliers))
            context.refinement.finalFit(context.data, model, inliers);
        else
            context.refinement.finalFitUnlessWorse(context.data, model, inliers);
        return outcome;
    }

private:
    static bool chanceInliersExpected(const TwoViewData& data, const std::vector<uchar>& inliers)
    {
        const auto outliers = static_cast<double>(
            inliers.size() - static_cast<size_t>(std::count(inliers.begin(), inliers.end(), 1)));
        return outliers * chanceOfBand(data, data.threshold) >= 1.0;
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
