// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "random sampling" of Fig. 1: every m-subset of the n points equally likely.

#include "framework/component_factories.hpp"
#include "framework/random.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class UniformSampler final : public Sampler
{
public:
    UniformSampler(int pointCount, int sampleSize, uint64_t seed)
        : pointCount_(static_cast<uint32_t>(pointCount)), sampleSize_(sampleSize), seed_(seed)
    {
        CV_Assert(pointCount >= sampleSize && sampleSize > 0);
    }

    void generateSample(int iteration, std::vector<int>& sample) const override
    {
        uint64_t state = iterationState(seed_, iteration);
        sample.resize(static_cast<size_t>(sampleSize_));
        drawDistinct(state, pointCount_, 0, sample);
    }

private:
    uint32_t pointCount_;
    int sampleSize_;
    uint64_t seed_;
};

} // namespace

std::unique_ptr<Sampler> createUniformSampler(int pointCount, int sampleSize, uint64_t seed)
{
    return std::make_unique<UniformSampler>(pointCount, sampleSize, seed);
}

} // namespace detail
} // namespace rcme
} // namespace cv
