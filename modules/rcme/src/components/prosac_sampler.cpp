// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "random sampling" of Fig. 1 with PROSAC (Chum & Matas, CVPR 2005): samples are drawn from
// progressively larger sets of the best-ranked correspondences, so that on a good ranking the
// first hypotheses are already all-inlier. The growth schedule is the paper's: with
// T_N = kGrowthLimit, T_m = T_N C(m,m)/C(N,m), T_{n+1} = T_n (n+1)/(n+1-m) and
// T'_{n+1} = T'_n + ceil(T_{n+1} - T_n), T'_m = 1, iteration t draws the n-th point and m - 1
// others among the n - 1 above it, n the smallest with T'_n >= t; past T'_N it is uniform.
// Sample j still depends only on (seed, j), like the uniform sampler's.

#include "framework/component_factories.hpp"
#include "framework/random.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The paper's T_N: how many samples the schedule takes to reach all N points.
constexpr double kGrowthLimit = 200000.0;

class ProsacSampler final : public Sampler
{
public:
    ProsacSampler(std::vector<int> order, int sampleSize, uint64_t seed)
        : order_(std::move(order)), sampleSize_(sampleSize), seed_(seed)
    {
        const int N = static_cast<int>(order_.size()), m = sampleSize;
        CV_Assert(N >= m && m > 0);
        double Tn = kGrowthLimit;
        for (int i = 0; i < m; ++i)
            Tn *= static_cast<double>(m - i) / (N - i);
        schedule_.assign(static_cast<size_t>(N - m + 1), 1.0); // T'_n for n = m .. N
        for (int n = m; n < N; ++n) {
            const double next = Tn * (n + 1) / (n + 1 - m);
            schedule_[static_cast<size_t>(n + 1 - m)] =
                schedule_[static_cast<size_t>(n - m)] + std::ceil(next - Tn);
            Tn = next;
        }
    }

    void generateSample(int iteration, std::vector<int>& sample) const override
    {
        const double t = iteration + 1.0;
        const auto it = std::lower_bound(schedule_.begin(), schedule_.end(), t);
        uint64_t state = iterationState(seed_, iteration);
        sample.resize(static_cast<size_t>(sampleSize_));
        if (it == schedule_.end()) { // past the schedule: uniform over all points
            drawDistinct(state, static_cast<uint32_t>(order_.size()), 0, sample);
        } else {
            const int n = sampleSize_ + static_cast<int>(it - schedule_.begin());
            sample[0] = n - 1; // the newest point, then m - 1 among the better ones
            drawDistinct(state, static_cast<uint32_t>(n - 1), 1, sample);
        }
        for (int& position : sample)
            position = order_[static_cast<size_t>(position)];
    }

private:
    std::vector<int> order_; //!< point indices, best ranked first
    int sampleSize_;
    uint64_t seed_;
    std::vector<double> schedule_;
};

} // namespace

std::unique_ptr<Sampler> createProsacSampler(std::vector<int> order, int sampleSize, uint64_t seed)
{
    return std::make_unique<ProsacSampler>(std::move(order), sampleSize, seed);
}

} // namespace detail
} // namespace rcme
} // namespace cv
