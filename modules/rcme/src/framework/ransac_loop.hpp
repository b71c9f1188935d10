// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP
#define OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP

#include "components/rival_motions.hpp"
#include "framework/components.hpp"

#include <limits>
#include <string>

namespace cv {
namespace rcme {
namespace detail {

//! What one run of the loop produced.
struct RansacResult
{
    Status status = STATUS_POOR_QUALITY_INPUT;
    std::string message;
    Model model;             //!< valid only on success
    Score score;             //!< of the returned model
    std::vector<uchar> mask; //!< inliers of the returned model, always data.size()
    //! With K: the inliers in front of both cameras (recoverPose's mask), set by
    //! ModelSpace::finish; empty otherwise.
    std::vector<uchar> inFront;
    int iterations = 0;
    int degenerateSamples = 0;
    bool outOfTime = false;   //!< the loop stopped at EstimatorComponents::deadline
    long long hypotheses = 0; //!< models the solver returned (several per sample for 7/5-point)
    //! Mean number of correspondences whose residual was evaluated per hypothesis, by the
    //! verifiers and by scoring; NaN when there was no hypothesis.
    double pointsPerHypothesis = std::numeric_limits<double>::quiet_NaN();
    //! The hypothesis with the most inliers the loop scored, candidate or not (inlierCount -1:
    //! none was scored); becomes the rejected model when no candidate exists.
    Model mostSupported;
    int mostSupportedInliers = -1;
    //! When the status is not success: the model the method would have returned without the
    //! test that failed, for diagnostics (Report::rejectedF, rejectedR, rejectedT).
    bool hasRejected = false;
    Model rejected;
    //! The motion is a planar scene's (ModelSpace::resolveHomography): Sampson costs do not tell
    //! its rivals.
    bool planar = false;
    //! The distinct motions among the candidates (with components.tracksRivals).
    std::vector<RivalMotions::Rival> rivals;
    /** The ambiguity test's measure: (C_rival - C) / sigma^2, C the truncated cost (MSAC, a
    point behind a camera costing as an outlier) of the returned motion and C_rival that of the
    best distinct rival, refitted; +inf when no rival came close, NaN when the test did not run. */
    double rivalCostGap = std::numeric_limits<double>::quiet_NaN();
};

/** Turns `result` into a failure with `status`: the mask is cleared and `model` is kept as the
rejected model. */
void rejectModel(RansacResult& result, Status status, const std::string& message,
                 const Model& model);

/** The RANSAC loop shared by every method: sample, instantiate, verify, score, keep the best
candidate, adapt the iteration bound; then refine the selected model, classify the points and
settle the estimate in its model space (ModelSpace::settleSelected), or when its motion fails
there, the first of the loop's distinct motions (result.rivals, best first) that settles. No
hypothesis that is not a candidate is ever returned: with none, the status says why. */
RansacResult runRansac(const TwoViewData& data, EstimatorComponents& components);

/** One whole estimation, the paper's Fig. 1 and what follows it: runRansac, the degeneracy test
(components.degeneracy), the final fit (finalizeModel), the final tests (components.finalTests)
and the model space's last decision (ModelSpace::finish). */
RansacResult estimateModel(const TwoViewData& data, EstimatorComponents& components);

/** Refines the selected model (result.model) on its inliers and classifies again, until the
inlier set stops changing; a refinement the scorer does not keep (Scorer::keepsRefinement) ends
it. */
void refineSelected(const TwoViewData& data, EstimatorComponents& components, RansacResult& result);

/** The final fit of a successful run's model and its covariance (Refiner::finalize), after the
decision on what the inliers determine (components.degeneracy): the model it fits is the one that is
returned. The mask becomes the points of that fit that the fitted model still holds. */
void finalizeModel(const TwoViewData& data, EstimatorComponents& components, RansacResult& result);

class CandidateSet;

/** runRansac's hypothesis loop alone (on several threads when components.parallel): adds the
candidates to `candidates`, sets result.iterations, degenerateSamples, hypotheses and
pointsPerHypothesis. Needs at least the solver's sample size of points. */
void searchHypotheses(const TwoViewData& data, EstimatorComponents& components,
                      CandidateSet& candidates, RansacResult& result);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP
