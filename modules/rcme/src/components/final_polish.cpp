// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The returned motion's robust polish, once the status is decided as success: the final fit's
// motion refitted on its inliers with a Cauchy loss (estimation/model_fit.cpp,
// polishFinalMotionOn), as PoseLib's last step. On sparse real pairs the least-squares fit is
// pulled by the few widest residuals among the inliers; the polish weighs them down
// (doc/results.md, "Sparse pairs: where the default loses accuracy against PoseLib"). It runs
// after every decision, so no status depends on it: the decisions read the least-squares fit
// their bounds were chosen with. The inliers become the points of the polish the polished motion
// still holds; the covariance is the polished motion's.

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* The loss's scale, a share of the inlier threshold: chosen on the tuning set (templeSR, KITTI 06)
between 0.25 and PoseLib's 0.5, higher AUC@10 on both, sparse and dense (doc/results.md, "The
final polish"). */
constexpr double kLossScaleOfThreshold = 0.25;

/* Reweighted steps from the least-squares fit: as many as the refinement's
(Params::refineIterations; Levenberg-Marquardt stops once the cost stops falling). Three, tried for
their cost, stopped short on a VO front end's thousand-odd tracks (doc/vo_front_end.md, "The
polish's steps"). */
class FinalPolish final : public EstimationStage
{
public:
    explicit FinalPolish(int maxIterations) : maxIterations_(maxIterations) {}

    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const TwoViewData& data = context.data;
        if (!estimate.model.motion() || !estimate.model.uncertainty.as<MotionUncertainty>())
            return {};
        std::vector<int> indices;
        maskIndices(estimate.mask, indices);
        StageOutcome outcome;
        Model& polished = outcome.model.emplace(estimate.model);
        if (!polishFinalMotionOn(data, indices, kLossScaleOfThreshold * data.threshold,
                                 maxIterations_, polished))
            return {};
        std::vector<uchar>& inliers = outcome.inliers.emplace();
        context.scorer.classify(data, polished, inliers);
        for (size_t i = 0; i < inliers.size(); ++i)
            inliers[i] = inliers[i] && estimate.mask[i];
        // Cheirality is decided: a polish that loses most of the points the estimate put in front
        // of both cameras (the mirrored decomposition puts them behind) or leaves too few to
        // determine the motion is not kept. Counted against the estimate's points in front, not
        // against all inliers: points beyond the distance limit count as in front of neither, and
        // on a highway's consecutive frames most inliers are that far (KITTI 01: 30-55 % of the
        // inliers in front before the polish), which turned every polish down there
        // (doc/vo_front_end.md, "Where the accuracy goes on KITTI 01 ORB").
        const int inFront =
            countPointsInFront(polished.motion()->R, polished.motion()->t, data.points1,
                               data.points2, data.Kinv, &inliers, nullptr);
        const int estimateInFront =
            countPointsInFront(estimate.model.motion()->R, estimate.model.motion()->t, data.points1,
                               data.points2, data.Kinv, &estimate.mask, nullptr);
        if (inFront < 2 * MotionTangent::kDof || 2 * inFront < estimateInFront)
            return {};
        return outcome;
    }

private:
    int maxIterations_;
};

} // namespace

std::unique_ptr<EstimationStage> createFinalPolish(int maxIterations)
{
    return std::make_unique<FinalPolish>(maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
