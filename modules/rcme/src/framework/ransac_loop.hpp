// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP
#define OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP

#include "framework/candidate_set.hpp"
#include "framework/rival_motions.hpp"

#include <limits>

namespace cv {
namespace rcme {
namespace detail {

//! What the hypothesis loop found: its candidates and what the stages after it read.
struct SearchResult
{
    CandidateSet candidates;
    int iterations = 0;
    int degenerateSamples = 0;
    bool outOfTime = false;   //!< the loop stopped at EstimatorComponents::deadline
    long long hypotheses = 0; //!< models the solver returned (several per sample for 7/5-point)
    //! Mean number of correspondences whose residual was evaluated per hypothesis, by the
    //! verifiers and by scoring; NaN when there was no hypothesis.
    double pointsPerHypothesis = std::numeric_limits<double>::quiet_NaN();
    //! The hypothesis with the most inliers the loop scored, candidate or not (inlierCount -1:
    //! none was scored): what a run without candidates would have returned.
    Model mostSupported;
    int mostSupportedInliers = -1;
    //! The distinct motions among the candidates (with components.tracksRivals).
    std::vector<RivalMotions::Rival> rivals;
};

/** The RANSAC loop shared by every method (on several threads when components.parallel):
sample, instantiate, verify, score, add the candidates to result.candidates, adapt the iteration
bound; then LO-RANSAC's inner sampling when the budget falls short. Needs at least the solver's
sample size of points. What follows the loop is the stages' (EstimatorComponents::stages). */
void searchHypotheses(const TwoViewData& data, EstimatorComponents& components,
                      SearchResult& result);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP
