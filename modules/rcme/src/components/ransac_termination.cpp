// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "termination" of Fig. 1: the usual adaptive bound N = log(1 - p) / log(1 - w^m) from the
// best inlier ratio w so far, or exactly N iterations as in the paper's experiments; and RCME's
// early termination (Sec. IV-D.2): stop once a candidate's mean entropy is below a preset bound.

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class AdaptiveTermination final : public Termination
{
public:
    AdaptiveTermination(double confidence, int maxIterations, int sampleSize)
        : confidence_(confidence), maxIterations_(maxIterations), sampleSize_(sampleSize),
          bound_(maxIterations)
    {
    }

    int iterationBound() const override { return bound_; }

    void update(const Score& best, int pointCount) override
    {
        const double inlierRatio = static_cast<double>(best.inlierCount) / pointCount;
        const double cleanSample = std::pow(inlierRatio, sampleSize_);
        if (cleanSample >= 1.0) {
            bound_ = 0;
            return;
        }
        if (cleanSample <= 0.0)
            return;
        const double needed = std::log(1.0 - confidence_) / std::log1p(-cleanSample);
        if (needed < maxIterations_)
            bound_ = std::min(bound_, static_cast<int>(std::ceil(needed)));
    }

private:
    double confidence_;
    int maxIterations_;
    int sampleSize_;
    int bound_;
};

class ExactTermination final : public Termination
{
public:
    explicit ExactTermination(int iterations) : iterations_(iterations) {}
    int iterationBound() const override { return iterations_; }
    void update(const Score&, int) override {}

private:
    int iterations_;
};

class EntropyTermination final : public Termination
{
public:
    EntropyTermination(std::unique_ptr<Termination> bound, double entropyBound)
        : bound_(std::move(bound)), entropyBound_(entropyBound)
    {
    }

    int iterationBound() const override { return satisfied_ ? 0 : bound_->iterationBound(); }

    void update(const Score& best, int pointCount) override
    {
        bound_->update(best, pointCount);
        satisfied_ = satisfied_ || (entropyBound_ > 0 && best.meanEntropy <= entropyBound_);
    }

private:
    std::unique_ptr<Termination> bound_;
    double entropyBound_;
    bool satisfied_ = false;
};

} // namespace

std::unique_ptr<Termination> createEntropyTermination(std::unique_ptr<Termination> bound,
                                                      double entropyBound)
{
    return std::make_unique<EntropyTermination>(std::move(bound), entropyBound);
}

std::unique_ptr<Termination> createAdaptiveTermination(double confidence, int maxIterations,
                                                       int sampleSize)
{
    return std::make_unique<AdaptiveTermination>(confidence, maxIterations, sampleSize);
}

std::unique_ptr<Termination> createExactTermination(int iterations)
{
    return std::make_unique<ExactTermination>(iterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
