// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "termination" of Fig. 1: the adaptive bound N = log(1 - p) / log(1 - q w^m) from the best
// inlier ratio w so far, where q is the fraction of all-inlier samples that give the right model
// (q = 1 is the usual bound; a noisy minimal sample can fit a wrong motion, as LO-RANSAC's
// authors observed, so q < 1 draws more); or exactly N iterations as in the paper's experiments;
// and RCME's early termination (Sec. IV-D.2): stop once a candidate's mean entropy is below a
// preset bound.

#include "framework/component_factories.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class AdaptiveTermination final : public Termination
{
public:
    AdaptiveTermination(double confidence, int maxIterations, int sampleSize,
                        double cleanSampleSuccessRate)
        : confidence_(confidence), maxIterations_(maxIterations), sampleSize_(sampleSize),
          cleanSampleSuccessRate_(cleanSampleSuccessRate), bound_(maxIterations)
    {
    }

    int iterationBound() const override { return bound_; }

    void update(const Score& best, int pointCount) override
    {
        const double inlierRatio = static_cast<double>(best.inlierCount) / pointCount;
        const double cleanSample = std::pow(inlierRatio, sampleSize_);
        // Every point an inlier: every sample is clean, and with q = 1 one sample suffices.
        if (cleanSample >= 1.0 && cleanSampleSuccessRate_ >= 1.0) {
            bound_ = 0;
            return;
        }
        const double needed =
            samplesForConfidence(confidence_, cleanSampleSuccessRate_ * cleanSample);
        if (needed < maxIterations_)
            bound_ = std::min(bound_, static_cast<int>(std::ceil(needed)));
    }

private:
    double confidence_;
    int maxIterations_;
    int sampleSize_;
    double cleanSampleSuccessRate_;
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
                                                       int sampleSize,
                                                       double cleanSampleSuccessRate)
{
    return std::make_unique<AdaptiveTermination>(confidence, maxIterations, sampleSize,
                                                 cleanSampleSuccessRate);
}

std::unique_ptr<Termination> createExactTermination(int iterations)
{
    return std::make_unique<ExactTermination>(iterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
