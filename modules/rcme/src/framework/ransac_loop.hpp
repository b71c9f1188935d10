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
    //! The hypothesis with the most inliers the loop scored, candidate or not (inlierCount -1:
    //! none was scored); becomes the rejected model when no candidate exists.
    Model mostSupported;
    int mostSupportedInliers = -1;
    //! When the status is not success: the model the method would have returned without the
    //! test that failed, for diagnostics (Report::rejectedF, rejectedR, rejectedT).
    bool hasRejected = false;
    Model rejected;
};

/** Turns `result` into a failure with `status`: the mask is cleared and `model` is kept as the
rejected model. */
void rejectModel(RansacResult& result, Status status, const std::string& message,
                 const Model& model);

/** The RANSAC loop shared by every method: sample, instantiate, verify, score, keep the best
candidate, adapt the iteration bound; then refine the selected model and classify the points.
No hypothesis that is not a candidate is ever returned: with none, the status says why. */
RansacResult runRansac(const TwoViewData& data, EstimatorComponents& components);

/** The final decision on a successful run whose inliers a homography explains as well as F
(Params::degeneracyTest). Without K, F is not determined: #STATUS_DEGENERATE_CONFIGURATION.
With K, a rotation that explains the inliers as well as the motion gives #STATUS_PURE_ROTATION
(model.R, t zero, F and E zero, the rotation's 3x3 covariance as uncertaintyDof 3); otherwise
the scene is planar (or nearly) and the motion is the one, among the selected motion and the
homography's decompositions (cv::decomposeHomographyMat), each refitted on the points it
explains, of least truncated cost (MSAC, a point behind a camera costing as an outlier); when a
distinct motion comes within ORB-SLAM's 0.75 of its support (inliers in front of both cameras),
cheirality cannot tell the two and the status is degenerate. The motion rejected by either
outcome is result.rejected. */
void decideDegeneracy(const TwoViewData& data, EstimatorComponents& components,
                      RansacResult& result);

/** The final fit of a successful run's model and its covariance (Refiner::finalize), after the
decision on what the inliers determine (decideDegeneracy): the model it fits is the one that is
returned. The mask becomes the points of that fit that the fitted model still holds. */
void finalizeModel(const TwoViewData& data, EstimatorComponents& components,
                   RansacResult& result);

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
