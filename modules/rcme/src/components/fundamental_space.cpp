// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The model space of uncalibrated data: the estimate is a fundamental matrix (7 DoF), as the
// hypotheses and their refinement already are.

#include "framework/model_space.hpp"

#include "framework/ransac_loop.hpp"

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

    bool settleSelected(const TwoViewData&, EstimatorComponents&, RansacResult&) const override
    {
        return true;
    }

    // Without K nothing of F is left determined: a family of F explains the points.
    void resolveHomography(const TwoViewData&, EstimatorComponents&, const Eigen::Matrix3d&,
                           RansacResult& result) const override
    {
        rejectModel(result, STATUS_DEGENERATE_CONFIGURATION,
                    "a homography explains the inliers as well as F (planar scene, pure rotation "
                    "or too little parallax): F is not determined without the camera matrix",
                    result.model);
    }

    void finish(const TwoViewData&, RansacResult&) const override {}
};

} // namespace

std::unique_ptr<ModelSpace> createFundamentalSpace()
{
    return std::make_unique<FundamentalSpace>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
