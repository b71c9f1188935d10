// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP
#define OPENCV_RCME_FRAMEWORK_RANSAC_LOOP_HPP

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
    int iterations = 0;
    int degenerateSamples = 0;
    bool outOfTime = false;   //!< the loop stopped at EstimatorComponents::deadline
    long long hypotheses = 0; //!< models the solver returned (several per sample for 7/5-point)
    //! Mean number of correspondences whose residual was evaluated per hypothesis, by the
    //! verifiers and by scoring; NaN when there was no hypothesis.
    double pointsPerHypothesis = std::numeric_limits<double>::quiet_NaN();
};

/** The RANSAC loop shared by every method: sample, instantiate, verify, score, keep the best
candidate, adapt the iteration bound; then refine the selected model and classify the points.
No hypothesis that is not a candidate is ever returned: with none, the status says why. */
RansacResult runRansac(const TwoViewData& data, EstimatorComponents& components);

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
