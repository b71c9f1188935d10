// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "random sampling" of Fig. 1: every m-subset of the n points equally likely.

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// SplitMix64: a well-mixed 64-bit sequence, identical on every platform (unlike the
// distributions of <random>), cheap to seed per iteration.
uint64_t splitMix64(uint64_t& state)
{
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Uniform integer in [0, bound) without modulo bias (Lemire's multiply-and-reject).
uint32_t uniformBelow(uint64_t& state, uint32_t bound)
{
    for (;;) {
        const uint64_t product = (splitMix64(state) >> 32) * static_cast<uint64_t>(bound);
        const uint32_t low = static_cast<uint32_t>(product);
        if (low >= (static_cast<uint32_t>(-bound) % bound))
            return static_cast<uint32_t>(product >> 32);
    }
}

class UniformSampler final : public Sampler
{
public:
    UniformSampler(int pointCount, int sampleSize, uint64_t seed)
        : pointCount_(static_cast<uint32_t>(pointCount)), sampleSize_(sampleSize), seed_(seed)
    {
        CV_Assert(pointCount >= sampleSize && sampleSize > 0);
    }

    void generateSample(int iteration, std::vector<int>& sample) override
    {
        uint64_t state = seed_ ^ (0xD1B54A32D192ED03ull * static_cast<uint64_t>(iteration + 1));
        sample.resize(static_cast<size_t>(sampleSize_));
        for (int k = 0; k < sampleSize_; ++k) {
            int index;
            do {
                index = static_cast<int>(uniformBelow(state, pointCount_));
            } while (std::find(sample.begin(), sample.begin() + k, index) != sample.begin() + k);
            sample[static_cast<size_t>(k)] = index;
        }
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
