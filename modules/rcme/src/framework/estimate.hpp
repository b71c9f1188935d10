// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_ESTIMATE_HPP
#define OPENCV_RCME_FRAMEWORK_ESTIMATE_HPP

// What passes between the stages after the loop (EstimationStage, framework/components.hpp): the
// estimate as it stands, and what one stage found about it. Only the pipeline
// (framework/estimation_pipeline.cpp) writes an Estimate; a stage reads it and returns a
// StageOutcome.

#include "framework/model.hpp"
#include "framework/two_view_input.hpp"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace cv {
namespace rcme {
namespace detail {

//! A model with its score and its inliers (1 per inlier, data.size() entries).
struct Fit
{
    Model model;
    Score score;
    std::vector<uchar> inliers;
};

//! What a pure rotation determines: R (x2 ~ K R K^-1 x1), not t.
struct Rotation
{
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    //! sigma^2 (J^T J)^-1 of the rotation increment omega, R exp([omega]x), when determined.
    std::optional<Eigen::Matrix3d> covariance;
};

//! A stage's decision on the estimate: its status and the reason, and the model it turns down.
struct Verdict
{
    Status status = STATUS_SUCCESS;
    std::string reason;
    //! The model the method would have returned without this decision, for diagnostics
    //! (Report::rejectedF, rejectedR, rejectedT).
    std::optional<Model> rejected;
};

//! What one stage found; an empty outcome keeps the estimate as it is.
struct StageOutcome
{
    //! A new model; its score and inliers when the stage found them.
    std::optional<Model> model;
    std::optional<Score> score;
    std::optional<std::vector<uchar>> inliers;
    std::optional<Verdict> verdict;
    //! The motion is a planar scene's: Sampson costs do not tell its rivals.
    bool planar = false;
    //! The rival motion decision's measure (Estimate::rivalCostGap).
    std::optional<double> rivalCostGap;
    //! recoverPose's mask (Estimate::inFront).
    std::optional<std::vector<uchar>> inFront;
    //! What is determined instead of the motion (Estimate::rotation).
    std::optional<Rotation> rotation;
    //! The motions the rival decision weighed (Estimate::weighedMotions).
    std::optional<std::vector<Model>> weighedMotions;
    //! The rivals it left unrefitted by their cost (Estimate::unweighedRivals).
    std::optional<std::vector<int>> unweighedRivals;

    //! The outcome that replaces the estimate with `fit`.
    static StageOutcome revised(Fit fit)
    {
        StageOutcome outcome;
        outcome.model = std::move(fit.model);
        outcome.score = fit.score;
        outcome.inliers = std::move(fit.inliers);
        return outcome;
    }
    //! The outcome that turns the estimate down with `status`.
    static StageOutcome rejecting(Status status, std::string reason, const Model& rejected)
    {
        StageOutcome outcome;
        outcome.verdict = Verdict{status, std::move(reason), rejected};
        return outcome;
    }
};

/** The estimate after the stages run so far. It stands (STATUS_SUCCESS) until a stage turns it
down; a failure has no inliers, except a pure rotation's (the rotation's inliers). */
struct Estimate
{
    Status status = STATUS_SUCCESS;
    std::string message;
    Model model;
    Score score;                //!< of the model, as the scorer last scored it
    std::vector<uchar> mask;    //!< inliers, always data.size()
    std::vector<uchar> inFront; //!< with K: recoverPose's mask; empty otherwise
    bool hasRejected = false;
    Model rejected;      //!< with hasRejected: Verdict::rejected of the failure
    bool planar = false; //!< StageOutcome::planar
    //! With STATUS_PURE_ROTATION: the rotation, which replaces the motion (the rejected model).
    std::optional<Rotation> rotation;
    /** The rival motion decision's measure: (C_rival - C) / sigma^2, C the truncated cost (MSAC,
    a point behind a camera costing as an outlier) of the returned motion and C_rival that of the
    best distinct rival, refitted; +inf when no rival came close, NaN when it did not run. */
    double rivalCostGap = std::numeric_limits<double>::quiet_NaN();
    /** The motions the rival motion decision weighed, each refitted on its own points (the
    loop's rivals, refittedRivalMotions, and the estimate it was given), so that a later stage
    weighs them again without refitting; empty when it did not run. */
    std::vector<Model> weighedMotions;
    /** The loop's rivals (indices in SearchResult::rivals) that the rival motion decision did not
    refit because their cost at the stated threshold, as the loop left them, was too high for the
    decision (refittedRivalMotions' gate); a later stage that weighs the rivals at another cap
    decides about those itself. */
    std::vector<int> unweighedRivals;

    Fit fit() const { return Fit{model, score, mask}; }
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_ESTIMATE_HPP
