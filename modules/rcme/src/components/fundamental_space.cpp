// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The model space of uncalibrated data: the estimate is a fundamental matrix (7 DoF), as the
// hypotheses and their refinement already are.

#include "framework/model_space.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class FundamentalSpace : public ModelSpace
{
public:
    bool liftHypothesis(const TwoViewData&, const std::vector<int>&, Model&,
                        std::vector<Eigen::Vector2d>&, std::vector<Eigen::Vector2d>&) const override
    {
        return true;
    }

    bool liftOn(const TwoViewData&, const std::vector<uchar>&, Model&, bool) const override
    {
        return true;
    }

    std::optional<Verdict> settleSelected(const TwoViewData&, const Refinement&, Scorer&,
                                          Fit&) const override
    {
        return std::nullopt;
    }

    // Without K nothing of F is left determined: a family of F explains the points.
    StageOutcome resolveHomography(const TwoViewData&, Scorer&, const Eigen::Matrix3d&,
                                   const Estimate& estimate) const override
    {
        return StageOutcome::rejecting(
            STATUS_DEGENERATE_CONFIGURATION,
            "a homography explains the inliers as well as F (planar scene, pure rotation or too "
            "little parallax): F is not determined without the camera matrix",
            estimate.model);
    }

    StageOutcome finish(const TwoViewData&, const Estimate&) const override { return {}; }
};

} // namespace

std::unique_ptr<ModelSpace> createFundamentalSpace()
{
    return std::make_unique<FundamentalSpace>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
