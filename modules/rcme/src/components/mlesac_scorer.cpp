// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// MLESAC's scorer (Torr & Zisserman, "MLESAC: A new robust estimator with application to
// estimating image geometry", CVIU 78(1), 2000): a hypothesis is scored by the likelihood of its
// residuals under a mixture of Gaussian inliers and uniform outliers instead of by its inlier
// count.
// - Residual: the Sampson distance e_i (pixels), which for a true match is one-dimensional
//   Gaussian noise of standard deviation sigma.
// - Mixture: p(e) = gamma N(e; 0, sigma^2) + (1 - gamma) / nu. The outliers' range nu is the
//   diagonal of the points' bounding box in image 2 (the paper uses the search window): a wrong
//   match's distance to its epipolar line spreads over that range. It is kept at least 10 sigma
//   so that the uniform density stays well below the Gaussian's peak on degenerate point sets.
// - Mixing weight gamma: per hypothesis by EM from 0.5 (E-step: posterior inlier probability
//   z_i = gamma N(e_i) / p(e_i); M-step: gamma = mean z_i), at most kMaxEmIterations steps or
//   until gamma changes by less than kEmTolerance. The inlier and outlier densities are far
//   apart (N(0) / (1 / nu) is ~300 for a 640x480 image and sigma = 1), so the posteriors are
//   nearly 0 or 1 and a few steps converge.
// - Score value: the negative log-likelihood -sum_i log p(e_i) at the fitted gamma (lower is
//   better), constants included.
// - Inliers (inlierCount and classify()): Sampson distance <= TwoViewData::threshold, as the
//   Standard method. Not "posterior > 0.5": that band, e^2 < 2 sigma^2 log(gamma nu / ((1 -
//   gamma) sqrt(2 pi) sigma)), widens with gamma and with the image size (~3.4 sigma at gamma =
//   0.5 on 640x480), and the chance bound that makes a hypothesis a candidate (minimalSupport) is
//   computed for the threshold band; with the same band the PQI guarantee holds as for Standard,
//   and the two methods differ only in how they rank hypotheses.
// - Candidate: inlierCount >= minimalSupport(threshold), so all-outlier input is still "poor
//   quality input".
// The Gaussian densities of a hypothesis are computed once into a buffer sized in the
// constructor (no allocation per score); threads evaluate on their own clone().

#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! Test hook (declared in test/test_mlesac.cpp): the mixing weight MLESAC's EM fits to `model`.
double mlesacMixingWeight(const TwoViewData& data, const Model& model);

namespace {

constexpr int kMaxEmIterations = 5;
constexpr double kEmTolerance = 1e-4;
// Keeps gamma inside (0, 1): at 0 or 1 EM cannot move any more and a far point's likelihood
// would vanish.
constexpr double kMinWeight = 1e-9;

class MlesacScorer final : public Scorer
{
public:
    MlesacScorer(const TwoViewData& data, int sampleSize, int maxIterations)
        : thresholdSquared_(data.threshold * data.threshold),
          inverseTwoVariance_(0.5 / (data.sigma * data.sigma)),
          gaussianPeak_(1.0 / (std::sqrt(2.0 * CV_PI) * data.sigma)),
          densities_(data.points1.size())
    {
        outlierDensity_ = 1.0 / std::max(boundingBoxSize(data.points2).norm(), 10.0 * data.sigma);
        minimalSupport_ = minimalSupport(data, data.threshold, sampleSize, maxIterations);
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        const int count = fillDensities(data, model);
        Score score;
        score.inlierCount = count;
        score.value = negativeLogLikelihood(fitMixingWeight());
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

    std::unique_ptr<Scorer> clone() const override { return std::make_unique<MlesacScorer>(*this); }

    double mixingWeight(const TwoViewData& data, const Model& model)
    {
        fillDensities(data, model);
        return fitMixingWeight();
    }

private:
    // Fills densities_ with each point's inlier density N(e_i; 0, sigma^2); returns the number
    // of points within the threshold (the classify() rule).
    int fillDensities(const TwoViewData& data, const Model& model)
    {
        if (densities_.size() != data.points1.size()) // only if called with other data
            densities_.resize(data.points1.size());
        int count = 0;
        for (size_t i = 0; i < densities_.size(); ++i) {
            const double d2 = sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]);
            count += d2 <= thresholdSquared_;
            densities_[i] = gaussianPeak_ * std::exp(-d2 * inverseTwoVariance_); // 0 if d2 = inf
        }
        return count;
    }

    double fitMixingWeight() const
    {
        if (densities_.empty())
            return 0.5;
        double gamma = 0.5;
        for (int iteration = 0; iteration < kMaxEmIterations; ++iteration) {
            const double outlier = (1.0 - gamma) * outlierDensity_;
            double posteriorSum = 0;
            for (double g : densities_) {
                const double inlier = gamma * g;
                posteriorSum += inlier / (inlier + outlier);
            }
            const double next = std::min(
                1.0 - kMinWeight, std::max(kMinWeight, posteriorSum / double(densities_.size())));
            const bool converged = std::abs(next - gamma) < kEmTolerance;
            gamma = next;
            if (converged)
                break;
        }
        return gamma;
    }

    double negativeLogLikelihood(double gamma) const
    {
        const double outlier = (1.0 - gamma) * outlierDensity_;
        double sum = 0;
        for (double g : densities_)
            sum -= std::log(gamma * g + outlier);
        return sum;
    }

    double thresholdSquared_;
    double inverseTwoVariance_; //!< 1 / (2 sigma^2)
    double gaussianPeak_;       //!< 1 / (sqrt(2 pi) sigma)
    double outlierDensity_ = 0; //!< 1 / nu
    int minimalSupport_ = 0;
    std::vector<double> densities_; //!< N(e_i; 0, sigma^2) of the last hypothesis evaluated
};

} // namespace

std::unique_ptr<Scorer> createMlesacScorer(const TwoViewData& data, int sampleSize,
                                           int maxIterations)
{
    return std::make_unique<MlesacScorer>(data, sampleSize, maxIterations);
}

double mlesacMixingWeight(const TwoViewData& data, const Model& model)
{
    // The sample size and iterations only set the scorer's chance support, not the weight.
    MlesacScorer scorer(data, /*sampleSize=*/8, /*maxIterations=*/1);
    return scorer.mixingWeight(data, model);
}

} // namespace detail
} // namespace rcme
} // namespace cv
