// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The model space of uncalibrated data: the estimate is a fundamental matrix (7 DoF), as the
// hypotheses and their refinement already are.

#include "framework/model_space.hpp"

#include "components/plane_parallax.hpp"

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

    ModelForm formOf(const Model&) const override { return ModelForm::kFundamental; }

    bool liftOn(const TwoViewData&, const std::vector<uchar>&, Model&, bool) const override
    {
        return true;
    }

    std::optional<Verdict> settleSelected(const TwoViewData&, const Refinement&, Scorer&,
                                          Fit&) const override
    {
        return std::nullopt;
    }

    // Without K a family of F, [e']x H, explains the plane's points: only the points off the
    // plane can fix the epipole.
    StageOutcome resolveHomography(const TwoViewData& data, const Refinement&, Scorer& scorer,
                                   const Eigen::Matrix3d& H,
                                   const Estimate& estimate) const override
    {
        return resolvePlaneAndParallax(data, scorer, H, estimate);
    }

    // Plane and parallax is a significance test of its own, so it also decides where H holds
    // most points but F wins GRIC: at most a fifth of F's support off the plane, over which
    // GRIC's margin is a draw. A pure rotation (H holds 80-90 % of the points F or H explain, F's
    // band also holding outliers along its lines) came back as success on a third of the scenes
    // with 60 true points (doc/f_only.md, "A dominant homography without K").
    double homographyShareToResolve() const override { return 0.8; }

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
