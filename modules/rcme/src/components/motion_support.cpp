// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "components/motion_support.hpp"

#include "estimation/model_fit.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Marks the points within the threshold of F; returns their squared Sampson distances.
std::vector<double> markWithinBand(const TwoViewData& data, const Eigen::Matrix3d& F,
                                   std::vector<uchar>& within)
{
    const double thresholdSquared = data.threshold * data.threshold;
    std::vector<double> distancesSquared(data.points1.size());
    within.resize(data.points1.size());
    for (size_t i = 0; i < within.size(); ++i) {
        distancesSquared[i] = sampsonDistanceSquared(F, data.points1[i], data.points2[i]);
        within[i] = distancesSquared[i] <= thresholdSquared;
    }
    return distancesSquared;
}

} // namespace

MotionSupport motionSupport(const TwoViewData& data, const Model& model, std::vector<uchar>& within,
                            std::vector<uchar>& inFront)
{
    const double thresholdSquared = data.threshold * data.threshold;
    const std::vector<double> distancesSquared = markWithinBand(data, model.F, within);
    MotionSupport fit;
    fit.support = countPointsInFront(model.motion()->R, model.motion()->t, data.points1,
                                     data.points2, data.Kinv, &within, &inFront);
    fit.cost = 0.0;
    for (size_t i = 0; i < within.size(); ++i)
        fit.cost += inFront[i] ? distancesSquared[i] : thresholdSquared;
    return fit;
}

double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F)
{
    return truncatedCost(data, F, data.threshold * data.threshold);
}

double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F, double capSquared)
{
    double cost = 0.0;
    for (size_t i = 0; i < data.points1.size(); ++i)
        cost += std::min(capSquared, sampsonDistanceSquared(F, data.points1[i], data.points2[i]));
    return cost;
}

MotionSupport refitOnOwnPoints(const TwoViewData& data, Model& motion, std::vector<uchar>& within,
                               std::vector<uchar>& inFront, int maxRounds)
{
    constexpr int kFitIterations = 20, kAlwaysRounds = 2;
    std::vector<int> inliers, previous;
    for (int round = 0; round < maxRounds; ++round) {
        markWithinBand(data, motion.F, within); // a round fits the band's points, in front or not
        maskIndices(within, inliers);
        if (round >= kAlwaysRounds && inliers == previous)
            break;
        previous = inliers;
        Model fitted = motion;
        if (fitModelOn(data, ModelForm::kMotion, inliers, kFitIterations, fitted))
            motion = fitted;
    }
    return motionSupport(data, motion, within, inFront);
}

namespace {

// `motion` refitted on its own points of `data` and its decomposition chosen again; none when it
// is no distinct motion from `selected` then.
std::optional<Model> refittedRival(const TwoViewData& data, const Model& motion,
                                   const Model& selected, std::vector<uchar>& within,
                                   std::vector<uchar>& inFront, int maxRounds)
{
    Model refitted = motion;
    if (refitOnOwnPoints(data, refitted, within, inFront, maxRounds).support <= 0)
        return std::nullopt;
    if (recoverMotion(data, within, refitted) && areDistinctMotions(refitted, selected))
        return refitted;
    return std::nullopt;
}

} // namespace

std::vector<Model> refittedRivalMotions(const TwoViewData& data,
                                        const std::vector<RivalMotions::Rival>& rivals,
                                        const Model& selected, int selectedInliers,
                                        const std::optional<RawCostGate>& gate,
                                        const std::optional<RefitScreen>& screen,
                                        std::vector<int>* skipped, int maxRounds)
{
    const TwoViewData subset = data.size() > static_cast<int>(kMaxIteratedPoints)
                                   ? evenlySpacedSubset(data, kMaxIteratedPoints)
                                   : TwoViewData();
    const TwoViewData& fitData = subset.points1.empty() ? data : subset;
    const bool screens = screen && data.size() > static_cast<int>(screen->points);
    const TwoViewData screenData =
        screens ? evenlySpacedSubset(data, screen->points) : TwoViewData();
    constexpr double kSupportShare = 0.5; // as RivalMotions' gate
    std::vector<Model> motions;
    std::vector<uchar> within, inFront;
    for (size_t r = 0; r < rivals.size(); ++r) {
        const RivalMotions::Rival& rival = rivals[r];
        if (rival.score.inlierCount < kSupportShare * selectedInliers ||
            !areDistinctMotions(rival.model, selected))
            continue;
        if (gate && truncatedCost(data, rival.model.F, gate->capSquared) > gate->maxCost) {
            if (skipped)
                skipped->push_back(static_cast<int>(r));
            continue;
        }
        if (screens) {
            std::optional<Model> screened =
                refittedRival(screenData, rival.model, selected, within, inFront, maxRounds);
            if (screened &&
                truncatedCost(data, screened->F, screen->capSquared) > screen->maxCost) {
                motions.push_back(std::move(*screened));
                continue;
            }
        }
        if (std::optional<Model> refitted =
                refittedRival(fitData, rival.model, selected, within, inFront, maxRounds))
            motions.push_back(std::move(*refitted));
    }
    return motions;
}

} // namespace detail
} // namespace rcme
} // namespace cv
