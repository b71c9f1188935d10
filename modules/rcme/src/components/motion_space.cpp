// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The model space of calibrated data: the estimate is a camera motion (R, t; 5 DoF). A hypothesis
// becomes a motion through the decomposition of its essential matrix that puts the points in
// front of both cameras; what a homography leaves determined is a rotation or a plane's motion.

#include "framework/model_space.hpp"

#include "components/homography_comparison.hpp"
#include "components/motion_support.hpp"
#include "estimation/model_fit.hpp"
#include "framework/refinement.hpp"
#include "geometry/epipolar.hpp"

#include <limits>

namespace cv {
namespace rcme {
namespace detail {

namespace {

const char* const kNoCheirality = "no decomposition of E puts the inliers in front of both cameras";

// ORB-SLAM's ambiguity ratio (Mur-Artal et al. 2015, homography reconstruction): a second
// motion with at least this share of the best one's support is not ruled out by cheirality.
constexpr double kAmbiguousSupportRatio = 0.75;
// ... and whose cost (motionSupport, in sigma^2) is within this of the best one's: twice a
// log-likelihood ratio of 10 is odds of about 150:1. The two motions of a homography's
// decomposition fit a plane's points about equally; a 5-point E refitted on a plane can stop in a
// shallow basin nearby (16 deg of translation away, 40 sigma^2 worse, on a test's scene), which
// support alone did not tell from a real ambiguity.
constexpr double kAmbiguousCostGap = 10.0;

// Which of E's decompositions is the motion is decided by cheirality on all the final inliers:
// a hypothesis decided it on its minimal sample alone, and refinement cannot change it (E and -E
// are the same geometry). When the decision changes the motion, its uncertainty is recomputed
// at the new one from the same inliers.
bool decideMotionOnInliers(const TwoViewData& data, Scorer& scorer, Fit& fit)
{
    Model& model = fit.model;
    const Motion before = *model.motion();
    if (!recoverMotion(data, fit.inliers, model))
        return false;
    if ((model.motion()->R - before.R).norm() < 1e-9 &&
        (model.motion()->t - before.t).norm() < 1e-9)
        return true;
    if (model.uncertainty.isKnown()) {
        std::vector<int> inliers;
        maskIndices(fit.inliers, inliers);
        fitModelOn(data, ModelForm::kMotion, inliers, 0, model);
    }
    fit.score = scorer.score(data, model);
    return true;
}

/* The comparison with the homography ran at the refined selection, before the final fit (all
inliers, in motion space) moves the motion. Where F explains the inliers better than the plane at
the fitted motion, their parallax decides between the plane's motions, and two that fit the plane
about equally are no ambiguity (two sparse-suite KITTI-01 pairs of 60 matches were flagged so with
a right motion, doc/results.md). */
bool homographyWinsAtFinalFit(const TwoViewData& data, const Refinement& refinement,
                              const Estimate& estimate)
{
    Model fitted = estimate.model;
    std::vector<uchar> inliers = estimate.mask;
    refinement.finalFit(data, fitted, inliers);
    return compareWithHomography(data, fitted.F, inliers).homographyExplainsInliers;
}

/* A planar scene's motion: among the selected motion and the homography's decompositions
(cv::decomposeHomographyMat), each refitted on the points it explains, the one of least cost
(motionSupport); when a distinct motion comes within ORB-SLAM's 0.75 of its support, cheirality
cannot tell the two and the status is degenerate, unless the homography loses to F at the final
fit's motion (above). */
StageOutcome resolvePlanarMotion(const TwoViewData& data, const Refinement& refinement,
                                 Scorer& scorer, const Eigen::Matrix3d& H, const Estimate& estimate)
{
    std::vector<Model> motions = homographyMotions(data, H);
    motions.insert(motions.begin(), estimate.model);
    std::vector<MotionSupport> fits(motions.size());
    std::vector<uchar> within, inFront;
    size_t best = 0;
    for (size_t m = 0; m < motions.size(); ++m) {
        fits[m] = refitOnOwnPoints(data, motions[m], within, inFront);
        if (fits[m].cost < fits[best].cost)
            best = m;
    }
    const double sigmaSquared = data.sigma * data.sigma;
    for (size_t m = 0; m < motions.size(); ++m) {
        const bool distinct = areDistinctMotions(motions[m], motions[best]);
        if (distinct && fits[m].support >= kAmbiguousSupportRatio * fits[best].support &&
            fits[m].cost - fits[best].cost < kAmbiguousCostGap * sigmaSquared) {
            if (!homographyWinsAtFinalFit(data, refinement, estimate))
                break;
            return StageOutcome::rejecting(
                STATUS_DEGENERATE_CONFIGURATION,
                "a homography explains the inliers (planar scene) and two of its motions put them "
                "in front of both cameras: the motion is not determined",
                motions[best]);
        }
    }
    Fit planar{motions[best], Score(), {}};
    scorer.classify(data, planar.model, planar.inliers);
    planar.score = scorer.score(data, planar.model);
    const bool acceptable = planar.score.isCandidate && fits[best].support > 0;
    StageOutcome outcome = StageOutcome::revised(std::move(planar));
    outcome.planar = true;
    if (!acceptable)
        outcome.verdict =
            Verdict{STATUS_POOR_QUALITY_INPUT,
                    "the motion of the planar scene fails the acceptance tests", motions[best]};
    return outcome;
}

class MotionSpace : public ModelSpace
{
public:
    bool liftHypothesis(const TwoViewData& data, const std::vector<int>& sample, Model& model,
                        std::vector<Eigen::Vector2d>& points1,
                        std::vector<Eigen::Vector2d>& points2) const override
    {
        return model.motion() || recoverMotionFromSample(data, sample, model, points1, points2);
    }

    // A hypothesis of an F solver, and the selected model until settleSelected lifts it, is still
    // an F (local optimisation and the first rounds of refinement fit it as one).
    ModelForm formOf(const Model& model) const override
    {
        return model.motion() ? ModelForm::kMotion : ModelForm::kFundamental;
    }

    bool liftOn(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model,
                bool redecide) const override
    {
        return (model.motion() && !redecide) || recoverMotion(data, inliers, model);
    }

    std::optional<Verdict> settleSelected(const TwoViewData& data, const Refinement& refinement,
                                          Scorer& scorer, Fit& selected) const override
    {
        if (!selected.model.motion()) {
            // The hypothesis becomes a motion: its essential matrix (FundamentalForm::essential,
            // which the refinement as F leaves as it was) decomposed with cheirality on the inliers
            // of the refined F, then refined in motion space. The inliers F gathers decide the
            // decomposition and where the motion's refinement starts (doc/performance.md,
            // "Refining F before the motion").
            if (!recoverMotion(data, selected.inliers, selected.model))
                return Verdict{STATUS_DEGENERATE_CONFIGURATION, kNoCheirality, selected.model};
            refinement.refineNewForm(data, selected);
        }
        if (!decideMotionOnInliers(data, scorer, selected))
            return Verdict{STATUS_DEGENERATE_CONFIGURATION, kNoCheirality, selected.model};
        return std::nullopt;
    }

    // A rotation that explains the inliers as well as the motion gives STATUS_PURE_ROTATION
    // (the rotation and its covariance, the motion turned down); otherwise the scene is planar (or
    // nearly) and its motion is resolvePlanarMotion's.
    StageOutcome resolveHomography(const TwoViewData& data, const Refinement& refinement,
                                   Scorer& scorer, const Eigen::Matrix3d& H,
                                   const Estimate& estimate) const override
    {
        RotationComparison rotation = compareWithRotation(data, estimate.model.F, estimate.mask);
        if (!rotation.rotationExplainsInliers)
            return resolvePlanarMotion(data, refinement, scorer, H, estimate);
        StageOutcome outcome;
        Rotation& pure = outcome.rotation.emplace();
        pure.R = rotation.R;
        if (rotation.hasCovariance)
            pure.covariance = rotation.covariance;
        outcome.inliers = std::move(rotation.inliers);
        outcome.verdict = Verdict{STATUS_PURE_ROTATION,
                                  "a rotation about the camera centre explains the inliers as well "
                                  "as a motion: R is determined, the translation is not",
                                  estimate.model};
        return outcome;
    }

    // A plane's answer with K is its motions (two of them fit it), asked only of a plane that
    // explains the inliers as well as the motion.
    double homographyShareToResolve() const override
    {
        return std::numeric_limits<double>::infinity();
    }

    // The final fit moved the motion: the inliers it leaves in front of both cameras are
    // recoverPose's mask, and a motion that leaves none is no motion of these points.
    StageOutcome finish(const TwoViewData& data, const Estimate& estimate) const override
    {
        StageOutcome outcome;
        std::vector<uchar>& inFront = outcome.inFront.emplace();
        if (estimate.status == STATUS_SUCCESS &&
            countPointsInFront(estimate.model.motion()->R, estimate.model.motion()->t, data.points1,
                               data.points2, data.Kinv, &estimate.mask, &inFront) == 0) {
            outcome.verdict =
                Verdict{STATUS_DEGENERATE_CONFIGURATION, kNoCheirality, estimate.model};
            inFront.assign(estimate.mask.size(), 0);
        } else if (estimate.status == STATUS_PURE_ROTATION) {
            inFront = estimate.mask;
        } else if (estimate.status != STATUS_SUCCESS) {
            inFront.assign(estimate.mask.size(), 0);
        }
        return outcome;
    }
};

} // namespace

std::unique_ptr<ModelSpace> createMotionSpace()
{
    return std::make_unique<MotionSpace>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
