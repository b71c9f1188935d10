// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The a-contrario tests of a calibrated estimate: is its support more than chance gives? Two
// questions, each a bound on the probability that chance alone gathers the support for any of the
// models a run could have chosen (Bonferroni, as the loop's minimalSupport; level 0.05):
// - the motion: its inliers against the share of *random pairings* of these very points that
//   its epipolar band holds. Below that, the matches carry no motion (STATUS_POOR_QUALITY_INPUT);
// - the translation: the inliers that move beyond the threshold once the rotation is removed
//   (the only ones t depends on) against random directions of that motion. Below that, the
//   points stand still or jitter and t is not determined (STATUS_UNDETERMINED_MOTION).

#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The level of both tests over all the models a run could have chosen.
constexpr double kLevel = 0.05;
// A run tests at most Params::maxIterations samples of 5 points, each giving up to 10 motions
// (the five-point solver's maximum); local optimisation refits them.
constexpr int kMotionSamplePoints = 5;
constexpr double kMotionsPerSample = 10;
// Given the rotation, the translation direction is determined by 2 moving points: C(m, 2)
// translations of m moving points.
constexpr int kTranslationSamplePoints = 2;
// Random pairings measured per call: each is the data paired with itself shifted by a share of
// n (spread by the golden ratio, so that no shift is near another or near 0 or n: tracks stored
// in image order would otherwise pair a point with a neighbour).
constexpr int kPairingShifts = 8;

/* Bernstein's bound on log P(S - mu >= excess) for S a sum of independent Bernoulli variables of
mean mu and variance `variance` (the moving points' chances differ, so S is not binomial). */
double logBernsteinTail(double excess, double variance)
{
    return excess > 0 ? -excess * excess / (2.0 * (variance + excess / 3.0)) : 0.0;
}

// The share of random pairings (x1_i, x2_{i+s mod n}) within F's band, over kPairingShifts shifts.
double chanceOfPairing(const TwoViewData& data, const Eigen::Matrix3d& F)
{
    const size_t n = data.points1.size();
    const double thresholdSquared = data.threshold * data.threshold;
    const double goldenShare = 0.5 * (std::sqrt(5.0) - 1.0);
    long long within = 0, pairings = 0;
    for (int j = 1; j <= kPairingShifts; ++j) {
        const double share = std::fmod(j * goldenShare, 1.0);
        const size_t shift = std::min(n - 1, std::max<size_t>(1, static_cast<size_t>(share * n)));
        within += countInSampsonBand(F, data.points1.data(), data.points2.data() + shift, n - shift,
                                     thresholdSquared);
        within += countInSampsonBand(F, data.points1.data() + (n - shift), data.points2.data(),
                                     shift, thresholdSquared);
        pairings += static_cast<long long>(n);
    }
    return static_cast<double>(within) / static_cast<double>(pairings);
}

struct TranslationSupport
{
    int moving = 0;        //!< points beyond the threshold of the rotation's prediction
    int movingInliers = 0; //!< those of them within the motion's band
    double chance = 0;     //!< moving inliers expected when the directions are random
    double variance = 0;   //!< their variance
};

/* The points that move beyond the threshold once the rotation is removed (x2 against
K R K^-1 x1, which every epipolar line of x1 passes through): a point closer to it is in the
band of every translation. A moving point at distance d is in the band (image-2 line distance up
to sqrt(2) threshold, which a Sampson distance within the threshold allows) when its direction
is within asin(sqrt(2) threshold / d) of the line: by chance with probability
2/pi asin(min(1, sqrt(2) threshold / d)) when directions are random. */
TranslationSupport translationSupport(const TwoViewData& data, const Motion& motion,
                                      const std::vector<uchar>& inliers)
{
    const Eigen::Matrix3d H = data.K * motion.R * data.Kinv;
    const double bandHalfWidth = std::sqrt(2.0) * data.threshold;
    TranslationSupport support;
    for (size_t i = 0; i < data.points1.size(); ++i) {
        const Eigen::Vector3d predicted = H * homogeneous(data.points1[i]);
        if (!(predicted.z() > 0))
            continue;
        const double d = (data.points2[i] - predicted.hnormalized()).norm();
        if (!(d > data.threshold))
            continue;
        ++support.moving;
        support.movingInliers += inliers[i] ? 1 : 0;
        const double p = 2.0 / CV_PI * std::asin(std::min(1.0, bandHalfWidth / d));
        support.chance += p;
        support.variance += p * (1.0 - p);
    }
    return support;
}

/* Without it, matches re-paired at random (an unusable frame) came back as a success: on KITTI's
KLT tracks shuffled, 29-124 inliers of 1400-3500: about the 2-4 % of random pairings that the
selected motion's band holds (the loop's minimalSupport assumes an epipolar band spread evenly
over the image, 1.6 %; an epipole among the points gathers more); and a camera standing still gave a
motion fitted to the 1-2 % of ORB matches that jitter by a pixel (doc/vo_front_end.md). */
class ChanceSupportTest final : public EstimationStage
{
public:
    ChanceSupportTest(int maxIterations, bool testsTranslation)
        : maxIterations_(maxIterations), testsTranslation_(testsTranslation)
    {
    }

    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const TwoViewData& data = context.data;
        const Model& model = estimate.model;
        if (!model.motion() || data.size() <= kMotionSamplePoints)
            return {};
        const double logLevel = std::log(kLevel);
        // the points in the motion's band, as the random pairings are counted (the final fit's
        // mask may be narrower)
        std::vector<uchar> band(data.points1.size());
        const int support = countInSampsonBand(model.F, data.points1, data.points2,
                                               data.threshold * data.threshold, band.data());
        const double chance = chanceOfPairing(data, model.F);
        // P(chance gives this support to one of the run's motions)
        const double motionChance = std::log(kMotionsPerSample * std::max(1, maxIterations_)) +
                                    logBinomialTail(data.size() - kMotionSamplePoints, chance,
                                                    support - kMotionSamplePoints);
        if (motionChance > logLevel)
            return StageOutcome::rejecting(
                STATUS_POOR_QUALITY_INPUT,
                cv::format("the motion's %d inliers of %d are no more than chance gives: a "
                           "random pairing of these points falls within its band with "
                           "probability %.4f (%.1f expected; chance gives one of the run's "
                           "motions as many with probability 10^%.1f > %.2f)",
                           support, data.size(), chance, chance * data.size(),
                           motionChance / std::log(10.0), kLevel),
                model);
        if (!testsTranslation_)
            return {};
        const TranslationSupport moving = translationSupport(data, *model.motion(), band);
        // P(chance aligns this many moving points with one of their C(m, 2) translations)
        const double translationChance =
            moving.moving < kTranslationSamplePoints
                ? 0.0
                : logBinomialCoefficient(moving.moving, kTranslationSamplePoints) +
                      logBernsteinTail(moving.movingInliers - moving.chance, moving.variance);
        if (translationChance > logLevel)
            return StageOutcome::rejecting(
                STATUS_UNDETERMINED_MOTION,
                cv::format("the translation is not determined: %d points move beyond the "
                           "threshold once the rotation is removed and %d of them lie on the "
                           "motion's epipolar lines, no more than random directions give (%.1f "
                           "expected); the other inliers fit any translation (a camera standing "
                           "still, or too little parallax)",
                           moving.moving, moving.movingInliers, moving.chance),
                model);
        return {};
    }

private:
    int maxIterations_;
    bool testsTranslation_;
};

} // namespace

std::unique_ptr<EstimationStage> createChanceSupportTest(int maxIterations, bool testsTranslation)
{
    return std::make_unique<ChanceSupportTest>(maxIterations, testsTranslation);
}

} // namespace detail
} // namespace rcme
} // namespace cv
