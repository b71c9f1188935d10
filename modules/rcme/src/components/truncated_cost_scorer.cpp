// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model verification" of Fig. 1(a) with MSAC's quality (Torr & Zisserman 2000): the sum of
// the squared Sampson distances, each capped (Params::scoring). A clean sample of noisy points
// can hold its true matches at 2-3 sigma, just outside the count's band, and lose by count to a
// wrong hypothesis with a few more points inside it, which then gets the local optimisation
// instead (doc/f_only.md, "Ranking hypotheses without K"). The candidate test and the inliers
// are the count's: the threshold's band, and a support beyond chance (minimalSupport).

#include "framework/component_factories.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The cap, in thresholds: 1.5 (2.94 sigma at the default threshold, about the 99.7 % quantile of a
// true match's Sampson distance) gained as many right F as MLESAC's likelihood on the synthetic
// hard cases; a cap at the threshold itself gained none, 2 thresholds raised the false alarms
// (doc/f_only.md).
constexpr double kCapInThresholds = 1.5;

// Points read between two checks of whether a hypothesis can still matter (as the count's).
constexpr size_t kBlock = 32;

class TruncatedCostScorer final : public Scorer
{
public:
    TruncatedCostScorer(const TwoViewData& data, int sampleSize, int maxIterations)
        : thresholdSquared_(data.threshold * data.threshold),
          capSquared_(kCapInThresholds * kCapInThresholds * thresholdSquared_),
          minimalSupport_(minimalSupport(data, data.threshold, sampleSize, maxIterations))
    {
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        Score score;
        int pointsRead = 0;
        read(data, model, nullptr, score, pointsRead);
        return score;
    }

    // A hypothesis stops being read once it can be neither the most supported one nor a rival
    // (its count cannot reach bar.inliersThatMatter) nor a candidate the set takes (short of the
    // support beyond chance, or a candidate of at most its cost so far holds at least as many
    // points as it still can). The cost so far only grows, so the run is that of every point
    // read.
    Score evaluateUpTo(const TwoViewData& data, const Model& model, const HypothesisBar& bar,
                       int& pointsRead) override
    {
        Score score;
        read(data, model, &bar, score, pointsRead);
        return score;
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        mask.resize(data.points1.size());
        countInSampsonBand(model.F, data.points1, data.points2, thresholdSquared_, mask.data());
    }

    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<TruncatedCostScorer>(*this);
    }

private:
    // Blocks of kBlock points in order, in evaluate() too, so that both sum the cost alike.
    void read(const TwoViewData& data, const Model& model, const HypothesisBar* bar, Score& score,
              int& pointsRead) const
    {
        const size_t n = data.points1.size();
        int inliers = 0;
        double cost = 0;
        size_t end = 0;
        while (end < n) {
            const size_t begin = end;
            end = std::min(n, begin + kBlock);
            addTruncatedSampsonCost(model.F, data.points1, data.points2, begin, end,
                                    thresholdSquared_, capSquared_, inliers, cost);
            if (bar && end < n && isOutOfReach(*bar, inliers + static_cast<int>(n - end), cost))
                break;
        }
        pointsRead = static_cast<int>(end);
        score.inlierCount = inliers;
        score.value = cost / thresholdSquared_;
        score.isCandidate = end == n && inliers >= minimalSupport_;
    }

    bool isOutOfReach(const HypothesisBar& bar, int reachable, double cost) const
    {
        if (reachable >= bar.inliersThatMatter)
            return false;
        return reachable < minimalSupport_ ||
               (bar.front &&
                reachable <= bar.front->mostInliersAtOrBelow(cost / thresholdSquared_));
    }

    double thresholdSquared_;
    double capSquared_;
    int minimalSupport_;
};

} // namespace

std::unique_ptr<Scorer> createTruncatedCostScorer(const TwoViewData& data, int sampleSize,
                                                  int maxIterations)
{
    return std::make_unique<TruncatedCostScorer>(data, sampleSize, maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
