// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Wald's sequential probability ratio test as a model verifier (Matas & Chum, "Randomized RANSAC
// with sequential probability ratio test", ICCV 2005), as Cov-RANSAC uses it: the points are
// checked in a fixed random order, and after each one the likelihood ratio
//     lambda_j = prod_r p(x_r | bad model) / p(x_r | good model)
// grows by delta / epsilon for a consistent point and by (1 - delta) / (1 - epsilon) for an
// inconsistent one; the hypothesis is rejected as soon as lambda_j > A. epsilon is the inlier
// ratio of a good model (the largest consistent ratio of a fully verified hypothesis so far),
// delta the consistent ratio of a bad one (the mean over rejected hypotheses); A follows them,
// from the paper's fixed point A = t_M C + 1 + log A (t_M: the cost of a hypothesis in point
// checks, C: the expected log-ratio per point of a bad model). Consistency is the scorer's own
// test (propagated uncertainty), so a hypothesis that passes is scored on the same terms.

#include "components/random.hpp"
#include "components/residual_uncertainty.hpp"
#include "framework/components.hpp"
#include "geometry/statistics.hpp"

#include <numeric>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// A hypothesis costs about as much as checking this many points: the minimal solve, the
// instantiation's fit on its sample and the covariance (measured order of magnitude).
constexpr double kModelCostInPoints = 200.0;

class SprtVerifier final : public ModelVerifier
{
public:
    SprtVerifier(const TwoViewData& data, const Params& params, uint64_t seed)
        : sigma_(data.sigma),
          inlierBound_(chiSquareQuantile(1.0 - params.alpha, params.consistencyDof)),
          order_(data.points1.size())
    {
        std::iota(order_.begin(), order_.end(), 0);
        // A fixed pseudo-random order, so a run is reproducible (Fisher-Yates).
        uint64_t state = seed ^ 0x5851F42D4C957F2Dull;
        for (size_t i = order_.size(); i > 1; --i)
            std::swap(order_[i - 1], order_[uniformBelow(state, static_cast<uint32_t>(i))]);
        updateThreshold();
    }

    bool isModelGood(const TwoViewData& data, const std::vector<int>&, Model& model) override
    {
        if (model.uncertaintyDof == 0)
            return false;
        const ResidualUncertainty uncertainty(model, sigma_);
        // In logarithms: the product of hundreds of factors would over- or underflow.
        const double consistentStep = std::log(delta_ / epsilon_);
        const double inconsistentStep = std::log((1.0 - delta_) / (1.0 - epsilon_));
        const double logThreshold = std::log(threshold_);
        double logRatio = 0.0;
        int checked = 0, consistent = 0;
        for (int i : order_) {
            double distanceSquared = 0, variance = 0;
            uncertainty.evaluate(data.points1[static_cast<size_t>(i)],
                                 data.points2[static_cast<size_t>(i)], false, distanceSquared,
                                 variance);
            ++checked;
            const bool isConsistent = distanceSquared <= inlierBound_ * variance;
            consistent += isConsistent;
            logRatio += isConsistent ? consistentStep : inconsistentStep;
            if (logRatio > logThreshold) {
                record(checked, true, static_cast<double>(consistent) / checked);
                return false;
            }
        }
        record(checked, false, static_cast<double>(consistent) / checked);
        return true;
    }

    long long pointsChecked() const override { return pointsChecked_; }
    // epsilon and delta follow every hypothesis tested so far.
    bool isSequential() const override { return true; }
    std::unique_ptr<ModelVerifier> clone() const override
    {
        return std::make_unique<SprtVerifier>(*this);
    }

private:
    void record(int checked, bool rejected, double consistentRatio)
    {
        pointsChecked_ += checked;
        if (rejected) {
            // delta: the mean consistent ratio of rejected (bad) hypotheses.
            ++rejected_;
            rejectedConsistentSum_ += consistentRatio;
            const double delta = std::min(0.5, std::max(1e-3, rejectedConsistentSum_ / rejected_));
            if (std::abs(delta - delta_) > 0.05 * delta_) {
                delta_ = delta;
                updateThreshold();
            }
        } else if (consistentRatio > epsilon_) {
            // epsilon: the inlier ratio of the best good hypothesis so far.
            epsilon_ = std::min(0.99, consistentRatio);
            updateThreshold();
        }
    }

    void updateThreshold()
    {
        // Keep the test meaningful: a good model must look more consistent than a bad one.
        epsilon_ = std::max(epsilon_, 1.5 * delta_);
        const double C = (1.0 - delta_) * std::log((1.0 - delta_) / (1.0 - epsilon_)) +
                         delta_ * std::log(delta_ / epsilon_);
        double A = kModelCostInPoints * C + 1.0;
        for (int i = 0; i < 10; ++i)
            A = kModelCostInPoints * C + 1.0 + std::log(A);
        threshold_ = std::max(A, 1.0 + 1e-9);
    }

    double sigma_;
    double inlierBound_;
    std::vector<int> order_;
    double epsilon_ = 0.1; //!< conservative starting values, as the paper suggests
    double delta_ = 0.01;
    double threshold_ = 1.0;
    long long pointsChecked_ = 0;
    long long rejected_ = 0;
    double rejectedConsistentSum_ = 0;
};

} // namespace

std::unique_ptr<ModelVerifier> createSprtVerifier(const TwoViewData& data, const Params& params,
                                                  uint64_t seed)
{
    return std::make_unique<SprtVerifier>(data, params, seed);
}

} // namespace detail
} // namespace rcme
} // namespace cv
