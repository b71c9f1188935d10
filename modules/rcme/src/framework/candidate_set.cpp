// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/candidate_set.hpp"

#include <algorithm>
#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

bool CandidateSet::add(const Model& model, const Score& score)
{
    if (steps_.mostInliersAtOrBelow(score.value) >= score.inlierCount)
        return false;
    front_.erase(std::remove_if(front_.begin(), front_.end(),
                                [&](const Candidate& c) {
                                    return score.value <= c.score.value &&
                                           score.inlierCount >= c.score.inlierCount;
                                }),
                 front_.end());
    front_.push_back({model, score});
    // A member of NaN value refuses nothing (no value is at least it), so it makes no step.
    steps_.steps.clear();
    for (const Candidate& c : front_)
        if (!std::isnan(c.score.value))
            steps_.steps.emplace_back(c.score.value, c.score.inlierCount);
    std::sort(steps_.steps.begin(), steps_.steps.end());
    for (size_t i = 1; i < steps_.steps.size(); ++i)
        steps_.steps[i].second = std::max(steps_.steps[i].second, steps_.steps[i - 1].second);
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

} // namespace detail
} // namespace rcme
} // namespace cv
