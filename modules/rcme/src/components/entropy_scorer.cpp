// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Boxes 2(a), 2(b) and 3(a) of Fig. 1(b):
// - 2(a) inliers by propagated uncertainty (eq. 4): d_i^2 / v_i <= F_dof^-1(1 - alpha), v_i the
//   variance of point i's Sampson distance (noise plus the model's covariance);
// - 2(b) inlier scoring by differential entropy (eq. 5): on the rank-one support of the Sampson
//   error vector, h_i = 1/2 log(2 pi e v_i); here as the excess over the noise floor
//   h_0 = 1/2 log(2 pi e sigma^2), i.e. 1/2 log(v_i / sigma^2), which does not depend on the
//   image's units;
// - 3(a) the inlier-set quality test (eq. 6, sign as written): Z = (psi - mu) / (s / sqrt(n_j))
//   <= Phi^-1(1 - alpha), psi and s the mean and standard deviation of the excess entropies, mu
//   Params::entropyThreshold; and the size test n_j / n >= lambda * omega_p, omega_p given or the
//   largest ratio of points within the noise-only band (v = sigma^2) of a quality-passing
//   hypothesis so far.
// The score is psi: the candidate of least mean entropy is selected (eq. 8).

#include "components/residual_uncertainty.hpp"
#include "framework/component_factories.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class EntropyScorer final : public Scorer
{
public:
    EntropyScorer(const TwoViewData& data, const EntropyOptions& options, int sampleSize,
                  int maxIterations)
        : sigma_(data.sigma), inlierBound_(data.consistencyBound),
          entropyThreshold_(options.entropyThreshold),
          zCritical_(normalQuantile(1.0 - options.alpha)), lambda_(options.inlierRatioFactor),
          priorInlierRatio_(options.priorInlierRatio), pointCount_(data.size())
    {
        // Chance support at the inlier band of a perfectly known model (v = sigma^2).
        minimalSupport_ =
            minimalSupport(data, std::sqrt(inlierBound_) * sigma_, sampleSize, maxIterations);
    }

    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        Score score;
        const double sigmaSquared = sigma_ * sigma_;
        int count = 0, certainCount = 0;
        double sum = 0, sumSquares = 0;
        forEachUncertainInlier(data, model, sigma_, inlierBound_,
                               [&](size_t, double distanceSquared, double variance) {
                                   certainCount += distanceSquared <= inlierBound_ * sigmaSquared;
                                   const double excessEntropy =
                                       0.5 * std::log(variance / sigmaSquared);
                                   ++count;
                                   sum += excessEntropy;
                                   sumSquares += excessEntropy * excessEntropy;
                               });
        score.inlierCount = count;
        if (count < 2)
            return score;
        const double psi = sum / count;
        const double deviation =
            std::sqrt(std::max(0.0, (sumSquares - count * psi * psi) / (count - 1)));
        score.value = psi;
        score.meanEntropy = psi;
        // With no spread the test degenerates to comparing psi with mu.
        const double z = deviation > 0 ? (psi - entropyThreshold_) / (deviation / std::sqrt(count))
                                       : (psi > entropyThreshold_ ? HUGE_VAL : -HUGE_VAL);
        const bool quality = z <= zCritical_;
        // omega_p from the inliers a perfectly known model would have (v = sigma^2): counts
        // inflated by a loose model's wide bands would make every tighter model fail the size
        // test, its refinement included.
        if (quality)
            score.runEvidence = static_cast<double>(certainCount) / pointCount_;
        // Chance support is judged on the noise-only band too: a loose model's wide bands catch
        // random points by their width alone. The size test waits for commit().
        score.isCandidate = quality && certainCount >= minimalSupport_;
        return score;
    }

    void commit(Score& score) override
    {
        bestQualityRatio_ = std::max(bestQualityRatio_, score.runEvidence);
        score.isCandidate = score.isCandidate && isStillCandidate(score);
    }

    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<EntropyScorer>(*this);
    }

    bool isStillCandidate(const Score& score) const override
    {
        const double omega = priorInlierRatio_ > 0 ? priorInlierRatio_ : bestQualityRatio_;
        return static_cast<double>(score.inlierCount) / pointCount_ >= lambda_ * omega;
    }

    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        classifyByUncertainty(data, model, sigma_, inlierBound_, mask);
    }

    // Any refinement that stays a candidate is kept, whatever its mean entropy: psi measures the
    // spread a model's own uncertainty adds, and a model refined on all its inliers has almost
    // none, so comparing psi across refinement steps compares noise and favours a refit that
    // sheds points. Gated on psi, the refinement stayed in the basin of a tight subset (clean
    // corridor data: median dq 0.0108 against 0.0034, doc/experiments_archive.md, "Box 4's gate").
    bool keepsRefinement(const Score&, const Score& refined) const override
    {
        return refined.isCandidate;
    }

private:
    double sigma_;
    double inlierBound_;
    double entropyThreshold_;
    double zCritical_;
    double lambda_;
    double priorInlierRatio_;
    int pointCount_;
    int minimalSupport_ = 0;
    double bestQualityRatio_ = 0; //!< omega_p estimated during the run
};

} // namespace

EntropyOptions entropyOptions(const Params& params)
{
    return {params.alpha, params.entropyThreshold, params.inlierRatioFactor,
            params.priorInlierRatio};
}

std::unique_ptr<Scorer> createEntropyScorer(const TwoViewData& data, const EntropyOptions& options,
                                            int sampleSize, int maxIterations)
{
    return std::make_unique<EntropyScorer>(data, options, sampleSize, maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
