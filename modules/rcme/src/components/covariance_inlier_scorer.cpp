// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Cov-RANSAC's quality (Raguram, Frahm & Pollefeys, ICCV 2009): the model's covariance is
// propagated to each point's residual and a point is an inlier when d^2 / v is within the
// chi-square bound (the same test as RCME's eq. 4, shared through forEachUncertainInlier); the
// hypothesis with the most inliers wins. Chance support is judged on the noise-only band, where
// a loose model's wide bands cannot inflate it.

#include "components/residual_uncertainty.hpp"
#include "framework/components.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class CovarianceInlierScorer final : public Scorer
{
public:
    CovarianceInlierScorer(const TwoViewData& data, const Params& params, int sampleSize)
        : sigma_(data.sigma),
          inlierBound_(chiSquareQuantile(1.0 - params.alpha, params.consistencyDof))
    {
        minimalSupport_ = minimalSupport(data, std::sqrt(inlierBound_) * sigma_, sampleSize,
                                         params.maxIterations);
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        const double noiseBound = inlierBound_ * sigma_ * sigma_;
        int count = 0, certainCount = 0;
        forEachUncertainInlier(data, model, sigma_, inlierBound_,
                               [&](size_t, double distanceSquared, double) {
                                   ++count;
                                   certainCount += distanceSquared <= noiseBound;
                               });
        Score score;
        score.inlierCount = count;
        score.value = -count;
        score.isCandidate = certainCount >= minimalSupport_;
        return score;
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        classifyByUncertainty(data, model, sigma_, inlierBound_, mask);
    }

    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<CovarianceInlierScorer>(*this);
    }

private:
    double sigma_;
    double inlierBound_;
    int minimalSupport_ = 0;
};

} // namespace

std::unique_ptr<Scorer> createCovarianceInlierScorer(const TwoViewData& data, const Params& params,
                                                     int sampleSize)
{
    return std::make_unique<CovarianceInlierScorer>(data, params, sampleSize);
}

} // namespace detail
} // namespace rcme
} // namespace cv
