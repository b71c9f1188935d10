// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The rivals weighed at the data's own noise (calibrated data, with the rival motion decision):
// the loop's distinct motions compared with the estimate by a truncated cost whose cap is the
// inlier threshold scaled to the noise the final fit measured, not to the stated one.

#include "components/motion_support.hpp"
#include "framework/component_factories.hpp"
#include "framework/ransac_loop.hpp"
#include "framework/refinement.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The noise of the points within the stated band of F, from the median of their squared Sampson
// distances (chi-square, 1 DoF; the band's truncation biases it alike for every F).
double bandNoise(const TwoViewData& data, const Eigen::Matrix3d& F)
{
    const double thresholdSquared = data.threshold * data.threshold;
    std::vector<double> squared;
    for (size_t i = 0; i < data.points1.size(); ++i) {
        const double d = sampsonDistanceSquared(F, data.points1[i], data.points2[i]);
        if (d <= thresholdSquared)
            squared.push_back(d);
    }
    if (squared.empty())
        return std::numeric_limits<double>::infinity();
    const auto middle = squared.begin() + static_cast<std::ptrdiff_t>(squared.size() / 2);
    std::nth_element(squared.begin(), middle, squared.end());
    return std::sqrt(*middle / chiSquareQuantile(0.5, 1));
}

/* MAGSAC++'s marginal loss (Barath et al., CVPR 2020: the squared residual's likelihood
marginalised over a uniform noise scale in (0, sigma_max], 4 DoF: a correspondence's coordinates, as
MAGSAC++ takes for epipolar geometry), with k sigma_max at the cap and scaled so that a point beyond
the cap costs the cap squared, as in the truncated cost (so the required gain keeps its meaning). A
truncation at the cap weighs a point 3-5 noise widths off a motion's lines almost as an inlier; the
marginal loss weighs points by how tightly they fit: on KITTI 01's (i, i+2) KLT pairs 14-16 and
15-17 the lateral motion's extra road tracks, near the cap, then no longer outweigh the tighter fit
of the far tracks to the true motion (doc/vo_front_end.md). With 4 DoF the incomplete gamma
functions have closed forms: gamma(2, x) = 1 - (1 + x) e^-x, Gamma(1, x) = e^-x. */
double marginalCost(const TwoViewData& data, const Eigen::Matrix3d& F, double capSquared)
{
    static const double kSquared = chiSquareQuantile(0.99, 4);
    const double sigmaMaxSquared = capSquared / kSquared;
    const double xCap = kSquared / 2.0;
    const double expCap = std::exp(-xCap);
    const double outside = sigmaMaxSquared / 2.0 * (1.0 - (1.0 + xCap) * expCap);
    const double scale = capSquared / outside;
    double total = 0.0;
    for (size_t i = 0; i < data.points1.size(); ++i) {
        const double d = sampsonDistanceSquared(F, data.points1[i], data.points2[i]);
        if (!(d < capSquared)) {
            total += capSquared;
            continue;
        }
        const double x = d / (2.0 * sigmaMaxSquared);
        const double e = std::exp(-x);
        total += scale * (sigmaMaxSquared / 2.0 * (1.0 - (1.0 + x) * e) + d / 4.0 * (e - expCap));
    }
    return total;
}

// A rival replaces the estimate only when its cost at the data's noise is lower by this many
// sigma^2 (as the planar path's ambiguity gap, components/motion_space.cpp): members of a planar
// scene's family of F differ by noise alone. On KITTI 01's consecutive KLT pairs the rivals that
// replaced a wrong motion were better by 30-1300 sigma^2 (doc/vo_front_end.md).
constexpr double kRequiredGain = 10.0;
// On a planar scene's motion a rival must also fit the points of its band at most at this share
// of the estimate's noise (bandNoise): on KITTI 01 the rivals that replaced a wrong plane's motion
// fitted theirs at 0.15-0.70 of it; on the synthetic planes of test_degeneracy.cpp, members of
// the family of F at 0.94-1.0.
constexpr double kRivalNoiseShare = 0.75;

/* The rivals the rival decision did not refit (Estimate::unweighedRivals: as the loop left them
they cost too much at the stated threshold to come within its margin) can still be the cheaper
motion at the data's noise: on KITTI 01 KLT (13, 15) the rival nearest the truth cost 1.46
sigma_hat^2 per point more than the estimate as the loop left it, 33 sigma_hat^2 less once
refitted (doc/vo_front_end.md). A minimal sample's motion costs more there than at the stated
cap, as every point's cap is lower: those within kMaxRawCostPerPoint sigma_hat^2 per point are
refitted here. Gate and refit run on an evenly spaced subset of kRivalSubsetPoints: on KITTI's pairs
the subset's refit takes a quarter of the full one's time and lands near it (on (13, 15) 40
sigma_hat^2 below the estimate against 33; the chosen rival gets its own final fit). */
constexpr double kMaxRawCostPerPoint = 2.0;

std::vector<Model> unweighedRivalsRefitted(const StageContext& context, const Estimate& estimate,
                                           double capSquared)
{
    if (estimate.unweighedRivals.empty())
        return {};
    std::vector<RivalMotions::Rival> unweighed;
    for (int r : estimate.unweighedRivals)
        unweighed.push_back(context.search.rivals[static_cast<size_t>(r)]);
    const TwoViewData subset = evenlySpacedSubset(context.data, kRivalSubsetPoints);
    const double measured = estimate.model.noiseSigma;
    const double mostRawCost = truncatedCost(subset, estimate.model.F, capSquared) +
                               kMaxRawCostPerPoint * measured * measured * subset.size();
    // Their support was weighed by the decision already (selectedInliers 0).
    return refittedRivalMotions(subset, unweighed, estimate.model, 0,
                                RawCostGate{capSquared, mostRawCost});
}

/* On a plane's motion the rival decision has not refitted the rivals; they are refitted here in
the band where they are weighed, the stage's cap: two rounds, and a rival that then costs less
than `mostCost` (it could replace the estimate) again from the loop's hypothesis, until its band
settles (kMaxRoundsAtDataNoise rounds at most: with a band that narrow the points come in a few at
a time; the others stay at two, which bounds the cost on large near-planar inputs). In the stated
threshold's band, two rounds left KITTI 01 KLT (19, 20)'s right rival 8.6 deg from the truth and
costlier than the wrong estimate the plane's path returned (marginal cost 2180 against 2008
sigma_hat^2); in the cap's band two rounds bring it to 1901, and settled it lands at 0.6 deg (1583)
and replaces it, while the estimate refitted the same way stays where it is (2015;
doc/vo_front_end.md). */
constexpr int kMaxRoundsAtDataNoise = 20;

std::vector<Model> rivalsRefittedAtDataNoise(const StageContext& context, const Estimate& estimate,
                                             double cap, double mostCost)
{
    // The refits' own subset of a large problem (refittedRivalMotions), taken once.
    TwoViewData atDataNoise = context.data.size() > static_cast<int>(kMaxIteratedPoints)
                                  ? evenlySpacedSubset(context.data, kMaxIteratedPoints)
                                  : context.data;
    atDataNoise.threshold = cap;
    atDataNoise.sigma = estimate.model.noiseSigma;
    std::vector<Model> refitted;
    for (const RivalMotions::Rival& rival : context.search.rivals) {
        const std::vector<RivalMotions::Rival> one{rival};
        std::vector<Model> motion =
            refittedRivalMotions(atDataNoise, one, estimate.model, estimate.score.inlierCount);
        if (motion.empty())
            continue;
        if (marginalCost(context.data, motion.front().F, cap * cap) < mostCost) {
            std::vector<Model> settled =
                refittedRivalMotions(atDataNoise, one, estimate.model, estimate.score.inlierCount,
                                     std::nullopt, std::nullopt, nullptr, kMaxRoundsAtDataNoise);
            if (!settled.empty())
                motion = std::move(settled);
        }
        refitted.push_back(std::move(motion.front()));
    }
    return refitted;
}

/* A stated threshold wider than the data's noise lets a wrong motion collect points a few noise
widths off its epipolar lines: on a highway's consecutive KLT pairs (doc/vo_front_end.md), tracks
stuck on repeating road texture, 3-5 px off the true lines, join the far tracks that fit any
translation once the rotation adapts, and at 1.96 px the wrong, nearly lateral motion explains
more points than the true one. At the noise of the tracks (0.25-0.35 px, from the final fit's
residuals) those points cost as outliers and the true motion explains the rest better. So each
rival motion of the loop with half the estimate's support (refittedRivalMotions) is weighed
against the estimate by a cost capped at (c sigma_hat / sigma)^2, c the threshold, sigma the
stated noise and sigma_hat the estimate's measured one (Model::noiseSigma; only when it is below
sigma: with noise as stated the rival decision, which already chose, weighs them at that cap),
the marginal cost (marginalCost) rather than MSAC's truncated one. The rival of
least cost replaces the estimate, with its own final fit, when it is better by kRequiredGain
sigma_hat^2. It runs on a planar scene's motion too (the homography may have fitted only the far
points of a deep scene), but there the rival must also fit its own points more tightly
(kRivalNoiseShare): on a real plane every member of the family of F fits the plane, the final
fit's noise is below the stated one because that family absorbs part of it, and a member that
fits a few points (and outliers) more tightly is no better motion. */
class RivalSelectionAtDataNoise final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const TwoViewData& data = context.data;
        const double measured = estimate.model.noiseSigma;
        if (!estimate.model.motion() || !(measured > 0.0) || measured >= data.sigma)
            return {};
        const double cap = data.threshold * measured / data.sigma;
        const double capSquared = cap * cap;
        double bestCost =
            marginalCost(data, estimate.model.F, capSquared) - kRequiredGain * measured * measured;
        const double noiseBound =
            estimate.planar ? kRivalNoiseShare * bandNoise(data, estimate.model.F) : 0.0;
        // The rival decision's refitted motions when it ran; on a plane's motion, which it
        // leaves, the rivals refitted here at the data's noise.
        std::vector<Model> rivals =
            estimate.weighedMotions.empty()
                ? rivalsRefittedAtDataNoise(context, estimate, cap, bestCost)
                : estimate.weighedMotions;
        for (Model& rival : unweighedRivalsRefitted(context, estimate, capSquared))
            rivals.push_back(std::move(rival));
        std::optional<Model> best;
        for (Model& rival : rivals) {
            if (!areDistinctMotions(rival, estimate.model))
                continue;
            const double cost = marginalCost(data, rival.F, capSquared);
            if (cost < bestCost && (!estimate.planar || bandNoise(data, rival.F) <= noiseBound)) {
                bestCost = cost;
                best = std::move(rival);
            }
        }
        if (!best)
            return {};
        Fit chosen{*best, Score(), {}};
        context.scorer.classify(data, chosen.model, chosen.inliers);
        chosen.score = context.scorer.score(data, chosen.model);
        if (!chosen.score.isCandidate)
            return {};
        context.refinement.finalFit(data, chosen.model, chosen.inliers);
        return StageOutcome::revised(std::move(chosen));
    }
};

} // namespace

std::unique_ptr<EstimationStage> createRivalSelectionAtDataNoise()
{
    return std::make_unique<RivalSelectionAtDataNoise>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
