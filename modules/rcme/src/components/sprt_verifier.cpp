// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Wald's sequential probability ratio test as a model verifier (Matas & Chum, "Randomized RANSAC
// with sequential probability ratio test", ICCV 2005): the points are checked in a fixed random
// order, and after each one the likelihood ratio
//     lambda_j = prod_r p(x_r | bad model) / p(x_r | good model)
// grows by delta / epsilon for a consistent point and by (1 - delta) / (1 - epsilon) for an
// inconsistent one; the hypothesis is rejected as soon as lambda_j > A. epsilon is the inlier
// ratio of a good model (the largest consistent ratio of a fully verified hypothesis so far),
// delta the consistent ratio of a bad one (the mean over rejected hypotheses); A follows them,
// from the paper's fixed point A = t_M C + 1 + log A (t_M: the cost of a hypothesis in point
// checks, C: the expected log-ratio per point of a bad model). Consistency is the scorer's own
// test, so a hypothesis that passes is scored on the same terms: the propagated uncertainty
// (Cov-RANSAC, RCME) or the threshold's Sampson band (Standard, MLESAC).

#include "components/residual_uncertainty.hpp"
#include "framework/component_factories.hpp"
#include "framework/random.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"

#include <numeric>
#include <optional>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The consistency test of the propagated uncertainty: d^2 <= bound * v (the paper's eq. 4).
// Point by point, as Cov-RANSAC's test is.
class UncertaintyConsistency
{
public:
    static constexpr size_t kBlock = 1;
    static constexpr bool kIsBand = false;
    // A hypothesis costs about as much as checking this many points: the minimal solve, the
    // instantiation's fit on its sample and the covariance (measured order of magnitude).
    static constexpr double kModelCostInPoints = 200.0;

    explicit UncertaintyConsistency(const TwoViewData& data)
        : sigma_(data.sigma), bound_(data.consistencyBound)
    {
    }
    bool prepare(const Model& model)
    {
        if (!model.uncertainty.isKnown())
            return false;
        uncertainty_.emplace(model, sigma_);
        return true;
    }
    int countConsistent(const Eigen::Vector2d* points1, const Eigen::Vector2d* points2,
                        size_t count) const
    {
        int consistent = 0;
        for (size_t i = 0; i < count; ++i) {
            double distanceSquared = 0, variance = 0;
            uncertainty_->evaluate(points1[i], points2[i], false, distanceSquared, variance);
            consistent += distanceSquared <= bound_ * variance;
        }
        return consistent;
    }

private:
    double sigma_;
    double bound_;
    std::optional<ResidualUncertainty> uncertainty_;
};

// The threshold's Sampson band, in blocks of points with the scorer's vectorized kernel: the
// ratio is tested after each block, so a bad hypothesis is rejected up to a block later than a
// point-by-point test would, for a third of the time per point.
class BandConsistency
{
public:
    static constexpr size_t kBlock = 16;
    static constexpr bool kIsBand = true;
    // A minimal solve (about 1.5 us per hypothesis of the 5- and 8-point solvers) against about
    // 1.2 ns per point in the band kernel.
    static constexpr double kModelCostInPoints = 1000.0;

    explicit BandConsistency(const TwoViewData& data)
        : thresholdSquared_(data.threshold * data.threshold)
    {
    }
    bool prepare(const Model& model)
    {
        F_ = model.F;
        return true;
    }
    int countConsistent(const Eigen::Vector2d* points1, const Eigen::Vector2d* points2,
                        size_t count) const
    {
        return countInSampsonBand(F_, points1, points2, count, thresholdSquared_);
    }

private:
    double thresholdSquared_;
    Eigen::Matrix3d F_;
};

template <class Consistency> class SprtVerifier final : public ModelVerifier
{
public:
    SprtVerifier(const TwoViewData& data, uint64_t seed) : consistency_(data)
    {
        std::vector<int> order(data.points1.size());
        std::iota(order.begin(), order.end(), 0);
        // A fixed pseudo-random order, so a run is reproducible (Fisher-Yates). The points are
        // copied in that order: a test reads them front to back, not scattered over a large set.
        uint64_t state = seed ^ 0x5851F42D4C957F2Dull;
        for (size_t i = order.size(); i > 1; --i)
            std::swap(order[i - 1], order[uniformBelow(state, static_cast<uint32_t>(i))]);
        ordered1_.reserve(order.size());
        ordered2_.reserve(order.size());
        for (int i : order) {
            ordered1_.push_back(data.points1[static_cast<size_t>(i)]);
            ordered2_.push_back(data.points2[static_cast<size_t>(i)]);
        }
        updateThreshold();
    }

    bool isModelGood(const TwoViewData&, const std::vector<int>&, Model& model) override
    {
        if (!consistency_.prepare(model))
            return false;
        // In logarithms: the product of hundreds of factors would over- or underflow.
        const double consistentStep = std::log(delta_ / epsilon_);
        const double inconsistentStep = std::log((1.0 - delta_) / (1.0 - epsilon_));
        const double logThreshold = std::log(threshold_);
        double logRatio = 0.0;
        int checked = 0, consistent = 0;
        const size_t n = ordered1_.size();
        for (size_t start = 0; start < n; start += Consistency::kBlock) {
            const size_t count = std::min(Consistency::kBlock, n - start);
            const int inBlock = consistency_.countConsistent(ordered1_.data() + start,
                                                             ordered2_.data() + start, count);
            checked += static_cast<int>(count);
            consistent += inBlock;
            logRatio += inBlock * consistentStep +
                        static_cast<double>(static_cast<int>(count) - inBlock) * inconsistentStep;
            if (logRatio > logThreshold) {
                record(checked, true, static_cast<double>(consistent) / checked);
                return false;
            }
        }
        record(checked, false, static_cast<double>(consistent) / checked);
        consistentOfPassed_ = consistent;
        return true;
    }

    // A model that passed was checked on every point.
    int bandInliersOfPassed() const override
    {
        return Consistency::kIsBand ? consistentOfPassed_ : -1;
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
        constexpr double cost = Consistency::kModelCostInPoints;
        double A = cost * C + 1.0;
        for (int i = 0; i < 10; ++i)
            A = cost * C + 1.0 + std::log(A);
        threshold_ = std::max(A, 1.0 + 1e-9);
    }

    Consistency consistency_;
    std::vector<Eigen::Vector2d> ordered1_, ordered2_;
    double epsilon_ = 0.1; //!< conservative starting values, as the paper suggests
    double delta_ = 0.01;
    double threshold_ = 1.0;
    long long pointsChecked_ = 0;
    int consistentOfPassed_ = -1;
    long long rejected_ = 0;
    double rejectedConsistentSum_ = 0;
};

} // namespace

std::unique_ptr<ModelVerifier> createSprtVerifier(const TwoViewData& data, uint64_t seed)
{
    return std::make_unique<SprtVerifier<UncertaintyConsistency>>(data, seed);
}

std::unique_ptr<ModelVerifier> createBandSprtVerifier(const TwoViewData& data, uint64_t seed)
{
    return std::make_unique<SprtVerifier<BandConsistency>>(data, seed);
}

} // namespace detail
} // namespace rcme
} // namespace cv
