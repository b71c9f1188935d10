// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model verification" of Fig. 1(a), the Standard method's quality: the number of points
// whose Sampson distance is within the threshold. A hypothesis is a candidate only when that
// number exceeds what chance would give (a non-randomness test in the spirit of PROSAC's), so
// all-outlier input ends as "poor quality input" instead of an 8-point fit to noise.

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

/** Probability that a random correspondence falls within `threshold` (Sampson distance) of a
hypothesis: the epipolar band of half-width sqrt(2) * threshold (the Sampson distance is at
least the image-2 line distance over sqrt(2)) across the diagonal of the points' bounding box in
image 2, over the box's area. Deliberately generous, so the test errs towards rejecting chance. */
double chanceInlierProbability(const TwoViewData& data)
{
    Eigen::Vector2d lo = data.points2.front(), hi = data.points2.front();
    for (const auto& x : data.points2) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    const Eigen::Vector2d extent = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(data.threshold));
    const double band = 2.0 * std::sqrt(2.0) * data.threshold * extent.norm();
    return std::min(1.0, band / (extent.x() * extent.y()));
}

/** Smallest k with P(Binomial(trials, p) >= k) <= level. */
int binomialTailBound(int trials, double p, double level)
{
    if (p >= 1.0)
        return trials + 1;
    const double ratio = p / (1.0 - p);
    double pmf = std::pow(1.0 - p, trials); // P(X = 0)
    double cdf = 0;
    for (int k = 0; k <= trials; ++k) {
        // 1 - cdf = P(X >= k)
        if (1.0 - cdf <= level)
            return k;
        cdf += pmf;
        pmf *= ratio * (trials - k) / (k + 1.0);
    }
    return trials + 1;
}

class InlierCountScorer final : public Scorer
{
public:
    InlierCountScorer(const TwoViewData& data, int sampleSize, int maxIterations)
        : thresholdSquared_(data.threshold * data.threshold)
    {
        // Bonferroni over the hypotheses a run may draw: 5 % for the whole run.
        const double level = 0.05 / std::max(1, maxIterations);
        minimalSupport_ = sampleSize + binomialTailBound(std::max(0, data.size() - sampleSize),
                                                         chanceInlierProbability(data), level);
    }

    Score score(const TwoViewData& data, const Model& model) override
    {
        int count = 0;
        for (size_t i = 0; i < data.points1.size(); ++i)
            count += sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]) <=
                     thresholdSquared_;
        Score score;
        score.inlierCount = count;
        score.value = -count;
        score.isCandidate = count >= minimalSupport_;
        return score;
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        mask.resize(data.points1.size());
        for (size_t i = 0; i < mask.size(); ++i)
            mask[i] = sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]) <=
                      thresholdSquared_;
    }

private:
    double thresholdSquared_;
    int minimalSupport_ = 0;
};

} // namespace

std::unique_ptr<Scorer> createInlierCountScorer(const TwoViewData& data, int sampleSize,
                                                int maxIterations)
{
    return std::make_unique<InlierCountScorer>(data, sampleSize, maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
