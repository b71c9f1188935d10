// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/ransac_loop.hpp"

#include "components/homography_comparison.hpp"
#include "components/random.hpp"
#include "estimation/model_fit.hpp"
#include "framework/candidate_set.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

const char* const kNoCheirality = "no decomposition of E puts the inliers in front of both cameras";

// Refines the selected model on its inliers and classifies again, until the inlier set stops
// changing (a refined model usually gathers inliers its minimal sample missed). A refinement is
// kept only if the scorer keeps it (Scorer::keepsRefinement), so a diverging refinement cannot
// spoil a good estimate.
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
        if (!c.scorer->keepsRefinement(result.score, refinedScore))
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

/* The most supported hypothesis of a run without candidates, as the method would have returned
it without its acceptance tests: refitted on its inliers and, with K, given its motion. Only a
diagnostic (Report::rejectedF...): a minimal sample's raw hypothesis would be judged far worse
than what the data support. */
Model polishRejected(const TwoViewData& data, EstimatorComponents& c, Model model)
{
    constexpr int kFitIterations = 20;
    std::vector<uchar> mask;
    c.scorer->classify(data, model, mask);
    if (data.calibrated && !model.hasMotion && !recoverMotion(data, mask, model))
        return model;
    std::vector<int> inliers;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i])
            inliers.push_back(static_cast<int>(i));
    Model fitted = model;
    if (fitModelOn(data, inliers, kFitIterations, fitted))
        model = fitted;
    if (data.calibrated)
        recoverMotion(data, mask, model);
    return model;
}

// Distinct motions the ambiguity test remembers: corridors and bas-relief scenes show two or
// three basins; the rest are minimal samples of one basin scattered by noise.
constexpr int kRivalCapacity = 8;

// With Params::isParallel, hypotheses are evaluated in batches of this many iterations. The size
// is fixed, not taken from the thread count, so the work done never depends on the threads.
constexpr int kParallelBatch = 64;

// The hypotheses of one iteration as evaluated, before they meet the state of the run.
struct IterationSlot
{
    std::vector<int> sample;
    int solutions = 0; //!< what the solver returned (0: degenerate sample)
    std::vector<Model> models;
    std::vector<uchar> alive; //!< passed the verifiers so far
    std::vector<Score> scores;
    long long pointsChecked = 0; //!< by the verifiers, over this iteration's hypotheses
};

// The components one thread evaluates hypotheses with: the loop's own for the first lane, copies
// with their own buffers for the others.
struct Lane
{
    MinimalSolver* solver = nullptr;
    std::vector<ModelVerifier*> verifiers; //!< those before the first sequential one
    Scorer* scorer = nullptr;
    std::unique_ptr<MinimalSolver> ownSolver;
    std::vector<std::unique_ptr<ModelVerifier>> ownVerifiers;
    std::unique_ptr<Scorer> ownScorer;
};

/* The hypothesis loop. Each batch of iterations is evaluated first (sample j from (seed, j),
solve, verify, Scorer::evaluate; on several threads when parallel), sequential verifiers (SPRT)
in iteration order between the two parallel steps; then the batch is committed in iteration order
on one thread: run-wide tests (Scorer::commit), candidate set, local optimisation, iteration
bound. Evaluation reads no state of the run, so the result is that of a sequential run whatever
the batch size and thread count (a sequential run is batches of one). Iterations beyond a bound
lowered inside a batch are evaluated but never committed. Every buffer is sized here: the loop
itself does not allocate. */
class HypothesisSearch
{
public:
    HypothesisSearch(const TwoViewData& data, EstimatorComponents& c) : data_(data), c_(c)
    {
        while (firstSequential_ < c.verifiers.size() &&
               !c.verifiers[firstSequential_]->isSequential())
            ++firstSequential_;
        for (size_t v = firstSequential_; v < c.verifiers.size(); ++v)
            sequentialVerifiers_.push_back(c.verifiers[v].get());
        batch_ = c.parallel ? kParallelBatch : 1;
        const int laneCount = c.parallel ? std::max(1, std::min(getNumThreads(), batch_)) : 1;
        lanes_.resize(static_cast<size_t>(laneCount));
        for (size_t l = 0; l < lanes_.size(); ++l) {
            Lane& lane = lanes_[l];
            if (l == 0) {
                lane.solver = c.solver.get();
                lane.scorer = c.scorer.get();
                for (size_t v = 0; v < firstSequential_; ++v)
                    lane.verifiers.push_back(c.verifiers[v].get());
                continue;
            }
            lane.ownSolver = c.solver->clone();
            lane.solver = lane.ownSolver.get();
            lane.ownScorer = c.scorer->clone();
            lane.scorer = lane.ownScorer.get();
            for (size_t v = 0; v < firstSequential_; ++v) {
                lane.ownVerifiers.push_back(c.verifiers[v]->clone());
                lane.verifiers.push_back(lane.ownVerifiers.back().get());
            }
        }
        if (c.localOptimizer)
            localInliers_.assign(static_cast<size_t>(data.size()), 0);
        if (c.innerSampling.samplesPerRound > 0)
            innerPool_.reserve(static_cast<size_t>(data.size()));
        if (c.ambiguityMargin > 0 && data.calibrated)
            rivals_ = std::make_unique<RivalMotions>(kRivalCapacity);
        const size_t solutions = static_cast<size_t>(c.solver->maxSolutions());
        slots_.resize(static_cast<size_t>(batch_));
        slots_.push_back(IterationSlot()); // the last one holds the inner samples
        for (IterationSlot& slot : slots_) {
            slot.sample.resize(static_cast<size_t>(c.solver->sampleSize()));
            slot.models.reserve(solutions);
            slot.alive.resize(solutions);
            slot.scores.resize(solutions);
        }
        innerDraw_.resize(static_cast<size_t>(c.solver->sampleSize()));
    }

    void run(CandidateSet& candidates, RansacResult& result)
    {
        int iteration = 0;
        while (iteration < c_.termination->iterationBound()) {
            // Checked per batch (one iteration when sequential): a clock read is cheap next to
            // a hypothesis.
            if (c_.deadline != 0 && getTickCount() >= c_.deadline) {
                result.outOfTime = true;
                break;
            }
            const int count = std::min(batch_, c_.termination->iterationBound() - iteration);
            evaluate(iteration, count);
            for (int k = 0; k < count && iteration < c_.termination->iterationBound();
                 ++k, ++iteration)
                commit(slots_[static_cast<size_t>(k)], candidates, result);
        }
        result.iterations = iteration;
        if (!result.outOfTime)
            sampleInsideBest(candidates, result);
        if (rivals_)
            result.rivals = rivals_->rivals();
        if (result.hypotheses > 0)
            result.pointsPerHypothesis =
                static_cast<double>(pointsEvaluated_) / static_cast<double>(result.hypotheses);
    }

private:
    // Calls step(lane, k) for k in [0, count), spread over the lanes when there are several.
    template <class Step> void forEachIteration(int count, const Step& step)
    {
        const int laneCount = static_cast<int>(lanes_.size());
        if (laneCount == 1) {
            for (int k = 0; k < count; ++k)
                step(lanes_[0], k);
            return;
        }
        parallel_for_(
            Range(0, laneCount),
            [&](const Range& range) {
                for (int l = range.start; l < range.end; ++l)
                    for (int k = l; k < count; k += laneCount)
                        step(lanes_[static_cast<size_t>(l)], k);
            },
            laneCount);
    }

    void evaluate(int firstIteration, int count)
    {
        const bool sequential = !sequentialVerifiers_.empty();
        forEachIteration(count, [&](Lane& lane, int k) {
            IterationSlot& slot = slots_[static_cast<size_t>(k)];
            c_.sampler->generateSample(firstIteration + k, slot.sample);
            slot.solutions = lane.solver->estimate(data_, slot.sample, slot.models);
            slot.pointsChecked = 0;
            for (size_t h = 0; h < slot.models.size(); ++h) {
                slot.alive[h] = passes(lane.verifiers, slot, h);
                if (slot.alive[h] && !sequential)
                    slot.scores[h] = lane.scorer->evaluate(data_, slot.models[h]);
            }
        });
        if (!sequential)
            return;
        for (int k = 0; k < count; ++k) {
            IterationSlot& slot = slots_[static_cast<size_t>(k)];
            for (size_t h = 0; h < slot.models.size(); ++h)
                slot.alive[h] = slot.alive[h] && passes(sequentialVerifiers_, slot, h);
        }
        forEachIteration(count, [&](Lane& lane, int k) {
            IterationSlot& slot = slots_[static_cast<size_t>(k)];
            for (size_t h = 0; h < slot.models.size(); ++h)
                if (slot.alive[h])
                    slot.scores[h] = lane.scorer->evaluate(data_, slot.models[h]);
        });
    }

    void commit(IterationSlot& slot, CandidateSet& candidates, RansacResult& result)
    {
        if (slot.solutions == 0) {
            ++result.degenerateSamples;
            return;
        }
        result.hypotheses += static_cast<long long>(slot.models.size());
        pointsEvaluated_ += slot.pointsChecked;
        for (size_t h = 0; h < slot.models.size(); ++h) {
            if (!slot.alive[h])
                continue;
            pointsEvaluated_ += data_.size(); // scored on every point
            Score& score = slot.scores[h];
            c_.scorer->commit(score);
            const Model& model = slot.models[h];
            if (score.inlierCount > result.mostSupportedInliers) {
                result.mostSupportedInliers = score.inlierCount;
                result.mostSupported = model;
            }
            if (rivals_ && score.isCandidate)
                rivals_->offer(data_, slot.sample, model, score);
            if (!score.isCandidate || !candidates.add(model, score))
                continue;
            if (c_.localOptimizer)
                optimizeLocally(data_, c_, model, candidates, localInliers_);
            if (const CandidateSet::Candidate* best = candidates.best(*c_.scorer))
                c_.termination->update(best->score, data_.size());
        }
    }

    // Whether the loop drew fewer samples than the confidence bound asks for the inlier ratio of
    // `best` (the loop stopped at Params::maxIterations, or ran exactly that many).
    bool fellShortOfTheBound(const CandidateSet::Candidate& best, int iterations) const
    {
        const EstimatorComponents::InnerSampling& inner = c_.innerSampling;
        const double inlierRatio = static_cast<double>(best.score.inlierCount) / data_.size();
        const double cleanSample = std::pow(inlierRatio, static_cast<double>(innerDraw_.size()));
        return samplesForConfidence(inner.confidence, inner.cleanSampleSuccessRate * cleanSample) >
               iterations;
    }

    /* LO-RANSAC's inner sampling (Chum et al. 2003), with minimal samples, after a loop that fell
    short of its confidence bound (a low inlier ratio, or a solver whose clean samples often fit
    a wrong model): minimal samples drawn from the best candidate's inliers are committed like the
    loop's, in rounds, while they improve the best and the bound is still unmet. A best of a
    wrong motion still holds mostly true inliers, so its inner samples are mostly clean where the
    loop's were not (w^m); minimal ones, because a fit to many of its inliers stays in its basin.
    A loop that met its bound is left as it is. The draws depend only on (seed, draw count); SPRT
    does not see them, so its state is that of the loop. */
    void sampleInsideBest(CandidateSet& candidates, RansacResult& result)
    {
        constexpr int kMaxRounds = 4;
        const EstimatorComponents::InnerSampling& inner = c_.innerSampling;
        if (inner.samplesPerRound <= 0)
            return;
        const size_t m = innerDraw_.size();
        IterationSlot& slot = slots_.back();
        Lane& lane = lanes_[0]; // the loop's own components: no evaluation is under way
        Score source;
        for (int round = 0; round < kMaxRounds; ++round) {
            if (c_.deadline != 0 && getTickCount() >= c_.deadline)
                return;
            const CandidateSet::Candidate* best = candidates.best(*c_.scorer);
            if (!best || (round > 0 && !best->score.isBetterThan(source)) ||
                !fellShortOfTheBound(*best, result.iterations))
                return;
            source = best->score;
            c_.scorer->classify(data_, best->model, localInliers_);
            innerPool_.clear();
            for (size_t i = 0; i < localInliers_.size(); ++i)
                if (localInliers_[i])
                    innerPool_.push_back(static_cast<int>(i));
            if (innerPool_.size() < 2 * m)
                return;
            for (int k = 0; k < inner.samplesPerRound; ++k) {
                uint64_t state = iterationState(~inner.seed, innerDrawn_++);
                drawDistinct(state, static_cast<uint32_t>(innerPool_.size()), 0, innerDraw_);
                for (size_t j = 0; j < m; ++j)
                    slot.sample[j] = innerPool_[static_cast<size_t>(innerDraw_[j])];
                slot.solutions = lane.solver->estimate(data_, slot.sample, slot.models);
                slot.pointsChecked = 0;
                for (size_t h = 0; h < slot.models.size(); ++h) {
                    slot.alive[h] = passes(lane.verifiers, slot, h);
                    if (slot.alive[h])
                        slot.scores[h] = lane.scorer->evaluate(data_, slot.models[h]);
                }
                commit(slot, candidates, result);
            }
        }
    }

    // The points a verifier checks are counted per slot, not read from the verifiers at the end:
    // a parallel run verifies iterations it does not commit, on copies of the verifiers.
    bool passes(const std::vector<ModelVerifier*>& verifiers, IterationSlot& slot, size_t h) const
    {
        for (ModelVerifier* verifier : verifiers) {
            const long long checkedBefore = verifier->pointsChecked();
            const bool isGood = verifier->isModelGood(data_, slot.sample, slot.models[h]);
            slot.pointsChecked += verifier->pointsChecked() - checkedBefore;
            if (!isGood)
                return false;
        }
        return true;
    }

    const TwoViewData& data_;
    EstimatorComponents& c_;
    size_t firstSequential_ = 0;
    int batch_ = 1;
    std::vector<Lane> lanes_;
    std::vector<IterationSlot> slots_;
    std::vector<ModelVerifier*> sequentialVerifiers_; //!< from the first sequential one on
    std::vector<uchar> localInliers_;                 //!< local optimisation's buffer, reused
    std::vector<int> innerPool_;                      //!< the best candidate's inliers
    std::vector<int> innerDraw_;                      //!< an inner sample, as pool positions
    int innerDrawn_ = 0;                              //!< inner samples drawn so far
    std::unique_ptr<RivalMotions> rivals_;            //!< with the ambiguity test only
    long long pointsEvaluated_ = 0; //!< residuals evaluated by verification and scoring
};

} // namespace

void rejectModel(RansacResult& result, Status status, const std::string& message,
                 const Model& model)
{
    result.status = status;
    result.message = message;
    result.rejected = model;
    result.hasRejected = true;
    std::fill(result.mask.begin(), result.mask.end(), 0);
}

namespace {

// ORB-SLAM's ambiguity ratio (Mur-Artal et al. 2015, homography reconstruction): a second
// motion with at least this share of the best one's support is not ruled out by cheirality.
constexpr double kAmbiguousSupportRatio = 0.75;
// ... and whose cost (planarFit, in sigma^2) is within this of the best one's: twice a
// log-likelihood ratio of 10 is odds of about 150:1. The two motions of a homography's
// decomposition fit a plane's points about equally; a 5-point E refitted on a plane can stop in a
// shallow basin nearby (16 deg of translation away, 40 sigma^2 worse, on a test's scene), which
// support alone did not tell from a real ambiguity.
constexpr double kAmbiguousCostGap = 10.0;

// Points within the threshold of the model's F (`within`); how many of them lie in front of both
// cameras (support); and the truncated cost of MSAC with cheirality: a point's squared Sampson
// distance, the squared threshold for a point outside the band or behind a camera.
struct PlanarFit
{
    int support = -1;
    double cost = std::numeric_limits<double>::infinity();
};

PlanarFit planarFit(const TwoViewData& data, const Model& model, std::vector<uchar>& within,
                    std::vector<uchar>& inFront)
{
    const double thresholdSquared = data.threshold * data.threshold;
    within.resize(data.points1.size());
    for (size_t i = 0; i < within.size(); ++i)
        within[i] =
            sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]) <= thresholdSquared;
    PlanarFit fit;
    fit.support = countPointsInFront(model.R, model.t, data.points1, data.points2, data.Kinv,
                                     &within, &inFront);
    fit.cost = 0.0;
    for (size_t i = 0; i < within.size(); ++i)
        fit.cost += inFront[i] ? sampsonDistanceSquared(model.F, data.points1[i], data.points2[i])
                               : thresholdSquared;
    return fit;
}

// MSAC's cost of F: each point's squared Sampson distance, at most the squared threshold.
double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F)
{
    const double thresholdSquared = data.threshold * data.threshold;
    double cost = 0.0;
    for (size_t i = 0; i < data.points1.size(); ++i)
        cost +=
            std::min(thresholdSquared, sampsonDistanceSquared(F, data.points1[i], data.points2[i]));
    return cost;
}

/* Refits a motion on the points within its own band, twice, and returns its fit (support:
those in front of both cameras). Not on the selected model's inliers: those pull every
other motion towards the selected one (on a plane the selected F is one of a family). */
PlanarFit refitOnOwnPoints(const TwoViewData& data, Model& motion)
{
    constexpr int kFitIterations = 20, kRounds = 2;
    std::vector<uchar> within, inFront;
    std::vector<int> inliers;
    for (int round = 0; round < kRounds; ++round) {
        planarFit(data, motion, within, inFront);
        inliers.clear();
        for (size_t i = 0; i < within.size(); ++i)
            if (within[i])
                inliers.push_back(static_cast<int>(i));
        Model fitted = motion;
        if (fitModelOn(data, inliers, kFitIterations, fitted))
            motion = fitted;
    }
    return planarFit(data, motion, within, inFront);
}

void resolvePlanarMotion(const TwoViewData& data, EstimatorComponents& c, const Eigen::Matrix3d& H,
                         RansacResult& result)
{
    std::vector<Model> motions = homographyMotions(data, H);
    motions.insert(motions.begin(), result.model);
    std::vector<PlanarFit> fits(motions.size());
    size_t best = 0;
    for (size_t m = 0; m < motions.size(); ++m) {
        fits[m] = refitOnOwnPoints(data, motions[m]);
        if (fits[m].cost < fits[best].cost)
            best = m;
    }
    const double sigmaSquared = data.sigma * data.sigma;
    for (size_t m = 0; m < motions.size(); ++m) {
        const bool distinct = areDistinctMotions(motions[m], motions[best]);
        if (distinct && fits[m].support >= kAmbiguousSupportRatio * fits[best].support &&
            fits[m].cost - fits[best].cost < kAmbiguousCostGap * sigmaSquared) {
            rejectModel(result, STATUS_DEGENERATE_CONFIGURATION,
                        "a homography explains the inliers (planar scene) and two of its motions "
                        "put them in front of both cameras: the motion is not determined",
                        motions[best]);
            return;
        }
    }
    result.planar = true;
    result.model = motions[best];
    c.scorer->classify(data, result.model, result.mask);
    result.score = c.scorer->score(data, result.model);
    if (!result.score.isCandidate || fits[best].support <= 0)
        rejectModel(result, STATUS_POOR_QUALITY_INPUT,
                    "the motion of the planar scene fails the acceptance tests", result.model);
}

} // namespace

void decideDegeneracy(const TwoViewData& data, EstimatorComponents& c, RansacResult& result)
{
    if (result.status != STATUS_SUCCESS)
        return;
    const HomographyComparison homography =
        compareWithHomography(data, result.model.F, result.mask);
    if (!homography.homographyExplainsInliers)
        return;
    if (!data.calibrated) {
        rejectModel(result, STATUS_DEGENERATE_CONFIGURATION,
                    "a homography explains the inliers as well as F (planar scene, pure rotation "
                    "or too little parallax): F is not determined without the camera matrix",
                    result.model);
        return;
    }
    const RotationComparison rotation = compareWithRotation(data, result.model.F, result.mask);
    if (rotation.rotationExplainsInliers) {
        result.rejected = result.model;
        result.hasRejected = true;
        Model pure;
        pure.hasMotion = true;
        pure.R = rotation.R;
        pure.t.setZero();
        if (rotation.hasCovariance) {
            pure.uncertaintyDof = 3;
            pure.covariance.topLeftCorner<3, 3>() = rotation.covariance;
        }
        result.model = pure;
        result.mask = rotation.inliers;
        result.status = STATUS_PURE_ROTATION;
        result.message = "a rotation about the camera centre explains the inliers as well as a "
                         "motion: R is determined, the translation is not";
        return;
    }
    resolvePlanarMotion(data, c, homography.H, result);
}

void resolveRivalMotions(const TwoViewData& data, EstimatorComponents& c, RansacResult& result)
{
    constexpr double kSupportShare = 0.5; // as RivalMotions' gate
    if (c.ambiguityMargin <= 0 || !data.calibrated || result.status != STATUS_SUCCESS ||
        !result.model.hasMotion || result.planar)
        return;
    // The cost is MSAC's, without the planar test's cheirality term: the depth sign of far
    // points flips with the noise, and counting them as outliers handed small-baseline corridors
    // to mirrored rivals. The four motions of one E share that cost, so a refitted rival's
    // decomposition is chosen again by cheirality on all the points of its band, as the selected
    // model's was: a rival whose sample's few points chose -t (forward motion, far points: on
    // KITTI every rival within the margin was the selected motion with t reversed) is then the
    // selected motion again, not an ambiguity.
    // A rival's refit and its decomposition on a subset of a large problem; costs on every point.
    const TwoViewData subset = data.size() > static_cast<int>(kMaxIteratedPoints)
                                   ? evenlySpacedSubset(data, kMaxIteratedPoints)
                                   : TwoViewData();
    const TwoViewData& fitData = subset.points1.empty() ? data : subset;
    std::vector<Model> motions{result.model};
    std::vector<double> costs{truncatedCost(data, result.model.F)};
    std::vector<uchar> within, inFront;
    for (const RivalMotions::Rival& rival : result.rivals) {
        if (rival.score.inlierCount < kSupportShare * result.score.inlierCount ||
            !areDistinctMotions(rival.model, result.model))
            continue;
        Model refitted = rival.model;
        if (refitOnOwnPoints(fitData, refitted).support <= 0)
            continue;
        planarFit(fitData, refitted, within, inFront);
        if (recoverMotion(fitData, within, refitted) &&
            areDistinctMotions(refitted, result.model)) {
            motions.push_back(refitted);
            costs.push_back(truncatedCost(data, refitted.F));
        }
    }
    size_t best = 0;
    for (size_t m = 1; m < motions.size(); ++m)
        if (costs[m] < costs[best])
            best = m;
    if (best != 0) {
        // A rival explains the data better than the loop's choice: it becomes the estimate.
        Model chosen = motions[best];
        std::vector<uchar> mask;
        c.scorer->classify(data, chosen, mask);
        const Score score = c.scorer->score(data, chosen);
        if (score.isCandidate) {
            result.model = chosen;
            result.mask = mask;
            result.score = score;
            finalizeModel(data, c, result);
            costs[best] = truncatedCost(data, result.model.F);
        } else {
            best = 0;
        }
    }
    double gap = std::numeric_limits<double>::infinity();
    for (size_t m = 0; m < motions.size(); ++m)
        if (m != best && areDistinctMotions(motions[m], motions[best]))
            gap = std::min(gap, (costs[m] - costs[best]) / (data.sigma * data.sigma));
    result.rivalCostGap = std::max(0.0, gap);
    if (result.rivalCostGap < c.ambiguityMargin)
        rejectModel(result, STATUS_UNDETERMINED_MOTION,
                    cv::format("a distinct motion explains the inliers about as well (cost gap "
                               "%.1f sigma^2 < Params.ambiguityMargin %.1f): the motion is not "
                               "determined",
                               result.rivalCostGap, c.ambiguityMargin),
                    result.model);
}

void checkMotionUncertainty(const TwoViewData& data, const EstimatorComponents& c,
                            RansacResult& result)
{
    const Model& model = result.model;
    if (!data.calibrated || result.status != STATUS_SUCCESS ||
        model.uncertaintyDof != MotionTangent::kDof)
        return;
    const Eigen::Matrix<double, 5, 5> covariance = model.covariance.topLeftCorner<5, 5>();
    const double rotationStd = rotationStdDeg(covariance).maxCoeff();
    const double translationStd = translationDirectionStdDeg(covariance);
    if (c.maxRotationStdDeg > 0 && rotationStd > c.maxRotationStdDeg)
        rejectModel(result, STATUS_UNDETERMINED_MOTION,
                    cv::format("the rotation's standard deviation %.2f deg exceeds "
                               "Params.maxRotationStdDeg %.2f: the motion is not determined",
                               rotationStd, c.maxRotationStdDeg),
                    model);
    else if (c.maxTranslationStdDeg > 0 && translationStd > c.maxTranslationStdDeg)
        rejectModel(result, STATUS_UNDETERMINED_MOTION,
                    cv::format("the translation direction's standard deviation %.2f deg exceeds "
                               "Params.maxTranslationStdDeg %.2f: the motion is not determined",
                               translationStd, c.maxTranslationStdDeg),
                    model);
}

void searchHypotheses(const TwoViewData& data, EstimatorComponents& components,
                      CandidateSet& candidates, RansacResult& result)
{
    HypothesisSearch(data, components).run(candidates, result);
}

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

    CandidateSet candidates;
    searchHypotheses(data, c, candidates, result);
    const int iteration = result.iterations;

    const CandidateSet::Candidate* best = candidates.best(*c.scorer);
    if (!best) {
        if (result.degenerateSamples == iteration) {
            result.status = STATUS_DEGENERATE_CONFIGURATION;
            result.message = "every minimal sample was degenerate (identical or collinear points)";
        } else {
            result.status = STATUS_POOR_QUALITY_INPUT;
            result.message =
                cv::format("no hypothesis passed the acceptance tests in %d iterations%s",
                           iteration, result.outOfTime ? " (Params.timeBudget ran out)" : "");
        }
        if (result.mostSupportedInliers >= 0) {
            result.rejected = polishRejected(data, c, result.mostSupported);
            result.hasRejected = true;
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
            rejectModel(result, STATUS_DEGENERATE_CONFIGURATION, kNoCheirality, result.model);
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
        rejectModel(result, STATUS_DEGENERATE_CONFIGURATION, kNoCheirality, result.model);
        return result;
    }
    if (!result.score.isCandidate) {
        rejectModel(result, STATUS_POOR_QUALITY_INPUT,
                    "the motion closest to the selected hypothesis fails the acceptance tests",
                    result.model);
        return result;
    }
    result.status = STATUS_SUCCESS;
    return result;
}

void finalizeModel(const TwoViewData& data, EstimatorComponents& c, RansacResult& result)
{
    if (result.status != STATUS_SUCCESS || !c.refiner)
        return;
    c.refiner->finalize(data, result.mask, result.model);
    // The final fit moves the model a little: the inliers are the points it used that the
    // final model still holds.
    std::vector<uchar> held;
    c.scorer->classify(data, result.model, held);
    for (size_t i = 0; i < held.size(); ++i)
        result.mask[i] = result.mask[i] && held[i];
}

} // namespace detail
} // namespace rcme
} // namespace cv
