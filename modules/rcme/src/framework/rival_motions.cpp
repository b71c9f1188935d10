// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/rival_motions.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {
// A hypothesis with less than this share of the best support cannot become a rival: after the
// loop only rivals with most of the selected model's support are refitted.
constexpr double kSupportShare = 0.5;
} // namespace

RivalMotions::RivalMotions(int capacity) : capacity_(static_cast<size_t>(std::max(1, capacity)))
{
    rivals_.reserve(capacity_);
    samplePoints1_.reserve(8);
    samplePoints2_.reserve(8);
}

int RivalMotions::leastSupportConsidered() const
{
    return static_cast<int>(std::ceil(kSupportShare * mostInliers_));
}

void RivalMotions::offer(const TwoViewData& data, const std::vector<int>& sample,
                         const Model& model, const Score& score)
{
    if (score.inlierCount < kSupportShare * mostInliers_)
        return;
    mostInliers_ = std::max(mostInliers_, score.inlierCount);
    Model motion = model;
    if (!motion.motion &&
        !recoverMotionFromSample(data, sample, motion, samplePoints1_, samplePoints2_))
        return;
    for (Rival& rival : rivals_) {
        if (areDistinctMotions(rival.model, motion))
            continue;
        if (score.isBetterThan(rival.score))
            rival = {motion, score};
        return;
    }
    if (rivals_.size() < capacity_) {
        rivals_.push_back({motion, score});
        return;
    }
    Rival* worst = &rivals_.front();
    for (Rival& rival : rivals_)
        if (worst->score.isBetterThan(rival.score))
            worst = &rival;
    if (score.isBetterThan(worst->score))
        *worst = {motion, score};
}

} // namespace detail
} // namespace rcme
} // namespace cv
