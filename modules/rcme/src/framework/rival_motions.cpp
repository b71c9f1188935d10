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

int RivalMotions::leastSupportConsidered(bool rankedByCount) const
{
    const int share = static_cast<int>(std::ceil(kSupportShare * mostInliers_));
    if (rivals_.size() < capacity_ || !rankedByCount)
        return share;
    // Full: a hypothesis enters only by a better score than a rival's, and for a score that is
    // the count that is a count above the least one kept.
    int least = rivals_.front().score.inlierCount;
    for (const Rival& rival : rivals_)
        least = std::min(least, rival.score.inlierCount);
    return std::max(share, least + 1);
}

size_t RivalMotions::worstIndex() const
{
    size_t worst = 0;
    for (size_t k = 1; k < rivals_.size(); ++k)
        if (rivals_[worst].score.isBetterThan(rivals_[k].score))
            worst = k;
    return worst;
}

void RivalMotions::offer(const TwoViewData& data, const std::vector<int>& sample,
                         const Model& model, const Score& score)
{
    if (score.inlierCount < kSupportShare * mostInliers_)
        return;
    mostInliers_ = std::max(mostInliers_, score.inlierCount);
    // Full, and no better than the worst rival: it can replace none, whatever its motion (the
    // decomposition below is most of the cost of an offer).
    if (rivals_.size() == capacity_ && !score.isBetterThan(rivals_[worstIndex()].score))
        return;
    Model motion = model;
    if (!motion.motion() &&
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
    // Better than the worst one (checked above): it takes its place.
    rivals_[worstIndex()] = {motion, score};
}

} // namespace detail
} // namespace rcme
} // namespace cv
