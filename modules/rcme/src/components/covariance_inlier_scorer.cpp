// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Cov-RANSAC's quality (Raguram, Frahm & Pollefeys, ICCV 2009): the model's covariance is
// propagated to each point's residual and a point is an inlier when d^2 / v is within the
// chi-square bound (the same test as RCME's eq. 4, shared through forEachUncertainInlier); the
// hypothesis with the most inliers wins. Chance support is judged on the noise-only band, where
// a loose model's wide bands cannot inflate it.

#include "components/residual_uncertainty.hpp"
#include "framework/component_factories.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// A point's residual variance is capped at twice the noise's: the model's share may at most equal
// the noise's, so a band is at most sqrt(2) times the noise-only band. Uncapped, a minimal
// sample's covariance can widen the bands over the whole image; every outlier is then an inlier
// and, as the most inliers win, the loosest hypothesis is selected (measured without K on the
// corridor: all 500 points, half of them outliers). First-order propagation is not valid that
// far anyway. The cap is chosen on the corridor (doc/experiments_archive.md, "Cov-RANSAC's
// band cap").
constexpr double kMaxVarianceInNoiseUnits = 2.0;

class CovarianceInlierScorer final : public Scorer
{
public:
    CovarianceInlierScorer(const TwoViewData& data, int sampleSize, int maxIterations)
        : sigma_(data.sigma), inlierBound_(data.consistencyBound)
    {
        minimalSupport_ =
            minimalSupport(data, std::sqrt(inlierBound_) * sigma_, sampleSize, maxIterations);
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        const double noiseBound = inlierBound_ * sigma_ * sigma_;
        int count = 0, certainCount = 0;
        forEachUncertainInlier(
            data, model, sigma_, inlierBound_,
            [&](size_t, double distanceSquared, double) {
                ++count;
                certainCount += distanceSquared <= noiseBound;
            },
            maxVariance());
        Score score;
        score.inlierCount = count;
        score.value = -count;
        score.isCandidate = certainCount >= minimalSupport_;
        return score;
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        classifyByUncertainty(data, model, sigma_, inlierBound_, mask, maxVariance());
    }

    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<CovarianceInlierScorer>(*this);
    }

private:
    double maxVariance() const { return kMaxVarianceInNoiseUnits * sigma_ * sigma_; }

    double sigma_;
    double inlierBound_;
    int minimalSupport_ = 0;
};

} // namespace

std::unique_ptr<Scorer> createCovarianceInlierScorer(const TwoViewData& data, int sampleSize,
                                                     int maxIterations)
{
    return std::make_unique<CovarianceInlierScorer>(data, sampleSize, maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
