// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "components/motion_support.hpp"

#include "estimation/model_fit.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

MotionSupport motionSupport(const TwoViewData& data, const Model& model, std::vector<uchar>& within,
                            std::vector<uchar>& inFront)
{
    const double thresholdSquared = data.threshold * data.threshold;
    within.resize(data.points1.size());
    for (size_t i = 0; i < within.size(); ++i)
        within[i] =
            sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]) <= thresholdSquared;
    MotionSupport fit;
    fit.support = countPointsInFront(model.R, model.t, data.points1, data.points2, data.Kinv,
                                     &within, &inFront);
    fit.cost = 0.0;
    for (size_t i = 0; i < within.size(); ++i)
        fit.cost += inFront[i] ? sampsonDistanceSquared(model.F, data.points1[i], data.points2[i])
                               : thresholdSquared;
    return fit;
}

double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F)
{
    const double thresholdSquared = data.threshold * data.threshold;
    double cost = 0.0;
    for (size_t i = 0; i < data.points1.size(); ++i)
        cost +=
            std::min(thresholdSquared, sampsonDistanceSquared(F, data.points1[i], data.points2[i]));
    return cost;
}

MotionSupport refitOnOwnPoints(const TwoViewData& data, Model& motion)
{
    constexpr int kFitIterations = 20, kRounds = 2;
    std::vector<uchar> within, inFront;
    std::vector<int> inliers;
    for (int round = 0; round < kRounds; ++round) {
        motionSupport(data, motion, within, inFront);
        maskIndices(within, inliers);
        Model fitted = motion;
        if (fitModelOn(data, inliers, kFitIterations, fitted))
            motion = fitted;
    }
    return motionSupport(data, motion, within, inFront);
}

} // namespace detail
} // namespace rcme
} // namespace cv
