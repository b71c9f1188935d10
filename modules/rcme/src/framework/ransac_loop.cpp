// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/ransac_loop.hpp"

#include "framework/candidate_set.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

bool passesVerifiers(EstimatorComponents& c, const TwoViewData& data,
                     const std::vector<int>& sample, Model& model)
{
    for (auto& verifier : c.verifiers)
        if (!verifier->isModelGood(data, sample, model))
            return false;
    return true;
}

// Refines the selected model on its inliers and classifies again, until the inlier set stops
// changing (a refined model usually gathers inliers its minimal sample missed). A refinement is
// kept only if the scorer still accepts it and likes it at least as much, so a diverging
// refinement cannot spoil a good estimate.
void refineSelected(const TwoViewData& data, EstimatorComponents& c, RansacResult& result)
{
    constexpr int kMaxRounds = 10;
    if (!c.refiner)
        return;
    for (int round = 0; round < kMaxRounds; ++round) {
        Model refined = result.model;
        if (!c.refiner->refine(data, result.mask, refined))
            return;
        const Score refinedScore = c.scorer->score(data, refined);
        if (!refinedScore.isCandidate || result.score.isBetterThan(refinedScore))
            return;
        result.model = refined;
        result.score = refinedScore;
        const std::vector<uchar> previousMask = result.mask;
        c.scorer->classify(data, result.model, result.mask);
        if (result.mask == previousMask)
            return;
    }
}

// Which of E's decompositions is the motion is decided by cheirality on all the final inliers:
// a hypothesis decided it on its minimal sample alone, and refinement cannot change it (E and -E
// are the same geometry). When the decision changes the motion, its uncertainty is recomputed
// at the new one from the same inliers.
bool decideMotionOnInliers(const TwoViewData& data, EstimatorComponents& c, RansacResult& result)
{
    Model& model = result.model;
    const Eigen::Matrix3d R = model.R;
    const Eigen::Vector3d t = model.t;
    if (!recoverMotion(data, result.mask, model))
        return false;
    if ((model.R - R).norm() < 1e-9 && (model.t - t).norm() < 1e-9)
        return true;
    if (model.uncertaintyDof > 0) {
        std::vector<int> inliers;
        for (size_t i = 0; i < result.mask.size(); ++i)
            if (result.mask[i])
                inliers.push_back(static_cast<int>(i));
        fitModelOn(data, inliers, 0, model);
    }
    result.score = c.scorer->score(data, model);
    return true;
}

// LO-RANSAC's step: a new candidate refitted on its own inliers competes as a candidate too (a
// minimal sample's hypothesis is noisy; its refit usually gathers more inliers, and the same
// inliers with a better-determined model).
void optimizeLocally(const TwoViewData& data, EstimatorComponents& c, const Model& candidate,
                     CandidateSet& candidates, std::vector<uchar>& inliers)
{
    Model refit = candidate;
    c.scorer->classify(data, refit, inliers);
    if (!c.localOptimizer->refine(data, inliers, refit))
        return;
    const Score score = c.scorer->score(data, refit);
    if (score.isCandidate)
        candidates.add(refit, score);
}

} // namespace

RansacResult runRansac(const TwoViewData& data, EstimatorComponents& c)
{
    RansacResult result;
    const int n = data.size();
    result.mask.assign(static_cast<size_t>(n), 0);
    const int m = c.solver->sampleSize();
    if (n < m) {
        result.status = STATUS_NOT_ENOUGH_POINTS;
        result.message = cv::format("%d correspondences, the minimal solver needs %d", n, m);
        return result;
    }

    std::vector<int> sample(static_cast<size_t>(m));
    std::vector<Model> models;
    models.reserve(static_cast<size_t>(c.solver->maxSolutions()));
    CandidateSet candidates;
    std::vector<uchar> inliers; // local optimisation's buffer, reused
    long long scoredHypotheses = 0;
    int iteration = 0;
    for (; iteration < c.termination->iterationBound(); ++iteration) {
        c.sampler->generateSample(iteration, sample);
        if (c.solver->estimate(data, sample, models) == 0) {
            ++result.degenerateSamples;
            continue;
        }
        for (Model& model : models) {
            ++result.hypotheses;
            if (!passesVerifiers(c, data, sample, model))
                continue;
            ++scoredHypotheses;
            const Score score = c.scorer->score(data, model);
            if (!score.isCandidate || !candidates.add(model, score))
                continue;
            if (c.localOptimizer)
                optimizeLocally(data, c, model, candidates, inliers);
            if (const CandidateSet::Candidate* best = candidates.best(*c.scorer))
                c.termination->update(best->score, n);
        }
    }
    result.iterations = iteration;
    long long pointsEvaluated = scoredHypotheses * n;
    for (const auto& verifier : c.verifiers)
        pointsEvaluated += verifier->pointsChecked();
    if (result.hypotheses > 0)
        result.pointsPerHypothesis = static_cast<double>(pointsEvaluated) / result.hypotheses;

    const CandidateSet::Candidate* best = candidates.best(*c.scorer);
    if (!best) {
        if (result.degenerateSamples == iteration) {
            result.status = STATUS_DEGENERATE_CONFIGURATION;
            result.message = "every minimal sample was degenerate (identical or collinear points)";
        } else {
            result.status = STATUS_POOR_QUALITY_INPUT;
            result.message =
                cv::format("no hypothesis passed the acceptance tests in %d iterations", iteration);
        }
        return result;
    }
    result.model = best->model;
    result.score = best->score;

    c.scorer->classify(data, result.model, result.mask);
    refineSelected(data, c, result);
    if (data.calibrated && !result.model.hasMotion) {
        // The (refined) F becomes a motion: the closest essential matrix, decomposed with
        // cheirality, then refined in motion space. Refining F first matters: the F of a noisy
        // minimal sample is far from any essential matrix.
        if (!recoverMotion(data, result.mask, result.model)) {
            result.status = STATUS_DEGENERATE_CONFIGURATION;
            result.message = "no decomposition of E puts the inliers in front of both cameras";
            std::fill(result.mask.begin(), result.mask.end(), 0);
            return result;
        }
        // The motion's maximum-likelihood fit on the F's inliers comes before classifying
        // again: the bare projection can lose most of them.
        if (c.refiner)
            c.refiner->refine(data, result.mask, result.model);
        result.score = c.scorer->score(data, result.model);
        c.scorer->classify(data, result.model, result.mask);
        refineSelected(data, c, result);
    }
    if (data.calibrated && !decideMotionOnInliers(data, c, result)) {
        result.status = STATUS_DEGENERATE_CONFIGURATION;
        result.message = "no decomposition of E puts the inliers in front of both cameras";
        std::fill(result.mask.begin(), result.mask.end(), 0);
        return result;
    }
    if (!result.score.isCandidate) {
        result.status = STATUS_POOR_QUALITY_INPUT;
        result.message = "the motion closest to the selected hypothesis fails the acceptance tests";
        std::fill(result.mask.begin(), result.mask.end(), 0);
        return result;
    }
    result.status = STATUS_SUCCESS;
    return result;
}

} // namespace detail
} // namespace rcme
} // namespace cv
