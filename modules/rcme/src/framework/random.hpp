// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_RANDOM_HPP
#define OPENCV_RCME_FRAMEWORK_RANDOM_HPP

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace cv {
namespace rcme {
namespace detail {

// SplitMix64: a well-mixed 64-bit sequence, identical on every platform (unlike the
// distributions of <random>), cheap to seed per iteration.
inline uint64_t splitMix64(uint64_t& state)
{
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Uniform integer in [0, bound) without modulo bias (Lemire's multiply-and-reject).
inline uint32_t uniformBelow(uint64_t& state, uint32_t bound)
{
    for (;;) {
        const uint64_t product = (splitMix64(state) >> 32) * static_cast<uint64_t>(bound);
        const uint32_t low = static_cast<uint32_t>(product);
        if (low >= (static_cast<uint32_t>(-bound) % bound))
            return static_cast<uint32_t>(product >> 32);
    }
}

//! The generator state of iteration `iteration` of a run seeded with `seed`.
inline uint64_t iterationState(uint64_t seed, int iteration)
{
    return seed ^ (0xD1B54A32D192ED03ull * static_cast<uint64_t>(iteration + 1));
}

//! Fills sample[first..] with distinct uniform indices below `bound` (also distinct from
//! sample[0..first)).
template <class Vector>
void drawDistinct(uint64_t& state, uint32_t bound, std::size_t first, Vector& sample)
{
    for (std::size_t k = first; k < sample.size(); ++k) {
        int index;
        do {
            index = static_cast<int>(uniformBelow(state, bound));
        } while (std::find(sample.begin(), sample.begin() + static_cast<long>(k), index) !=
                 sample.begin() + static_cast<long>(k));
        sample[k] = index;
    }
}

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_RANDOM_HPP
