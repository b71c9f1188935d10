// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/candidate_set.hpp"

namespace cv {
namespace rcme {
namespace detail {

bool CandidateSet::add(const Model& model, const Score& score)
{
    for (const Candidate& c : front_)
        if (c.score.value <= score.value && c.score.inlierCount >= score.inlierCount)
            return false;
    front_.erase(std::remove_if(front_.begin(), front_.end(),
                                [&](const Candidate& c) {
                                    return score.value <= c.score.value &&
                                           score.inlierCount >= c.score.inlierCount;
                                }),
                 front_.end());
    front_.push_back({model, score});
    return true;
}

const CandidateSet::Candidate* CandidateSet::best(const Scorer& scorer) const
{
    const Candidate* best = nullptr;
    // Entries are in order of discovery, so strict comparison keeps the earliest of equals.
    for (const Candidate& c : front_)
        if (scorer.isStillCandidate(c.score) && (!best || c.score.isBetterThan(best->score)))
            best = &c;
    return best;
}

void CandidateSet::frontSteps(std::vector<std::pair<double, int>>& steps) const
{
    steps.clear();
    for (const Candidate& c : front_)
        steps.emplace_back(c.score.value, c.score.inlierCount);
    std::sort(steps.begin(), steps.end());
    for (size_t i = 1; i < steps.size(); ++i)
        steps[i].second = std::max(steps[i].second, steps[i - 1].second);
}

} // namespace detail
} // namespace rcme
} // namespace cv
