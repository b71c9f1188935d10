// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model verification" of Fig. 1(a), the Standard method's quality: the number of points
// whose Sampson distance is within the threshold. A hypothesis is a candidate only when that
// number exceeds what chance would give (minimalSupport), so all-outlier input ends as "poor
// quality input" instead of an 8-point fit to noise.

#include "framework/component_factories.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class InlierCountScorer final : public Scorer
{
public:
    InlierCountScorer(const TwoViewData& data, int sampleSize, int maxIterations)
        : thresholdSquared_(data.threshold * data.threshold)
    {
        minimalSupport_ = minimalSupport(data, data.threshold, sampleSize, maxIterations);
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        return scoreOf(countInSampsonBand(model.F, data.points1, data.points2, thresholdSquared_));
    }

    // The score is the count, so a hypothesis that cannot reach the count that matters cannot
    // become the best candidate: most bad hypotheses stop after a fraction of the points.
    Score evaluateUpTo(const TwoViewData& data, const Model& model, const HypothesisBar& bar,
                       int& pointsRead) override
    {
        size_t read = 0;
        Score score = scoreOf(countInSampsonBandReaching(
            model.F, data.points1, data.points2, thresholdSquared_, bar.inliersThatMatter, read));
        pointsRead = static_cast<int>(read);
        if (read < data.points1.size())
            score.isCandidate = false;
        return score;
    }

    bool ranksByInlierCount() const override { return true; }

    std::optional<Score> scoreOfBandCount(int bandInliers) const override
    {
        return scoreOf(bandInliers);
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        mask.resize(data.points1.size());
        countInSampsonBand(model.F, data.points1, data.points2, thresholdSquared_, mask.data());
    }

    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<InlierCountScorer>(*this);
    }

private:
    Score scoreOf(int count) const
    {
        Score score;
        score.inlierCount = count;
        score.value = -count;
        score.isCandidate = count >= minimalSupport_;
        return score;
    }

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
