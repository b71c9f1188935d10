// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_CANDIDATE_SET_HPP
#define OPENCV_RCME_FRAMEWORK_CANDIDATE_SET_HPP

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

/** Box 3(b) of Fig. 1(b): the candidate solution set C (paper eq. 7) and the selection of its
member of least score (eq. 8); empty at the end means failure, "poor quality input".

Some acceptance tests depend on the whole run (RCME's size test against an inlier ratio that
only grows), so a candidate can stop qualifying later, and the best one at the end need not be
the best one when it was found. The set therefore keeps every candidate that no other beats in
both score and inlier count (a Pareto front, small in practice): whatever the final tests
reject, the best survivor is among them. For inlier counting alone it holds one model. */
class CandidateSet
{
public:
    struct Candidate
    {
        Model model;
        Score score;
    };

    //! Room for a front far larger than seen in practice, so adding rarely allocates.
    CandidateSet()
    {
        front_.reserve(32);
        steps_.steps.reserve(32);
    }

    //! Adds a candidate unless an earlier one is at least as good in both score and inlier
    //! count (ties keep the earliest). Returns whether it was added.
    bool add(const Model& model, const Score& score);

    //! The candidate of least score that `scorer` still accepts, or null.
    const Candidate* best(const Scorer& scorer) const;

    //! What add() refuses, as steps (the loop's HypothesisBar reads it).
    const CandidateFront& front() const { return steps_; }

private:
    std::vector<Candidate> front_;
    CandidateFront steps_; //!< front_ as steps, rebuilt when it changes
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_CANDIDATE_SET_HPP
