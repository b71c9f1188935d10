// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_RIVAL_MOTIONS_HPP
#define OPENCV_RCME_FRAMEWORK_RIVAL_MOTIONS_HPP

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** The ambiguity test's memory (Params::ambiguityMargin): the best hypothesis of each distinct
motion (areDistinctMotions) among the loop's candidates, so that after the loop a motion other
than the selected one can be refitted and compared with it. Minimal samples of one noisy scene
can fall into two basins (the corridor's lateral translation and its mirror, a bas-relief
rival); the loop keeps only the best of all, and a rival it saw tells that the data hold two
answers. Fed in iteration order on one thread; sized once, it does not allocate while fed. */
class RivalMotions
{
public:
    struct Rival
    {
        Model model; //!< with its motion, decided by cheirality on its sample
        Score score;
    };

    //! Keeps at most `capacity` motions, the best-scored ones.
    explicit RivalMotions(int capacity);

    /** A candidate hypothesis of calibrated data and its sample. Ignored when it has less than
    half the support of the best offered so far (no rival of the final estimate then). */
    void offer(const TwoViewData& data, const std::vector<int>& sample, const Model& model,
               const Score& score);

    /** The least inlier count at which offer() can change the rivals: half the best offered so
    far, and, when the scores rank by inlier count alone (`rankedByCount`) and all `capacity`
    places are taken, one more than the least count kept. */
    int leastSupportConsidered(bool rankedByCount) const;
    //! One per distinct motion seen, in no particular order.
    const std::vector<Rival>& rivals() const { return rivals_; }

private:
    //! The place of the rival of the worst score (the first of equals), which a better one takes.
    size_t worstIndex() const;

    size_t capacity_;
    int mostInliers_ = 0;
    std::vector<Rival> rivals_;
    std::vector<Eigen::Vector2d> samplePoints1_, samplePoints2_;
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_RIVAL_MOTIONS_HPP
