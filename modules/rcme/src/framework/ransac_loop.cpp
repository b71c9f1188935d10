// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/ransac_loop.hpp"

#include "framework/random.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

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

// Distinct motions the loop remembers (RivalMotions): corridors and bas-relief scenes show two or
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
    //! The band's inliers a verifier counted on every point (Scorer::scoreOfBandCount), else -1.
    std::vector<int> bandInliers;
    std::vector<Score> scores;
    //! Residuals evaluated by the verifiers and the scorer, over this iteration's hypotheses.
    long long pointsRead = 0;
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
bound. Evaluation reads no state of the run but what a hypothesis must reach, taken before the
batch (HypothesisBar: a scorer that stops below it changes nothing the run would keep), so the
result is that of a sequential run whatever the batch size and thread count (a sequential run is
batches of one). Iterations beyond a bound lowered inside a batch are evaluated but never committed.
Every buffer is sized here: the loop itself does not allocate. */
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
        if (c.tracksRivals)
            rivals_ = std::make_unique<RivalMotions>(kRivalCapacity);
        const size_t solutions = static_cast<size_t>(c.solver->maxSolutions());
        slots_.resize(static_cast<size_t>(batch_));
        slots_.push_back(IterationSlot()); // the last one holds the inner samples
        for (IterationSlot& slot : slots_) {
            slot.sample.resize(static_cast<size_t>(c.solver->sampleSize()));
            slot.models.reserve(solutions);
            slot.alive.resize(solutions);
            slot.scores.resize(solutions);
            slot.bandInliers.resize(solutions);
        }
        innerDraw_.resize(static_cast<size_t>(c.solver->sampleSize()));
    }

    void run(SearchResult& result)
    {
        CandidateSet& candidates = result.candidates;
        int iteration = 0;
        while (iteration < c_.termination->iterationBound()) {
            // Checked per batch (one iteration when sequential): a clock read is cheap next to
            // a hypothesis.
            if (c_.deadline != 0 && getTickCount() >= c_.deadline) {
                result.outOfTime = true;
                break;
            }
            const int count = std::min(batch_, c_.termination->iterationBound() - iteration);
            setBar(result);
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

    /* What a hypothesis must reach to change the run (HypothesisBar), set before a batch is
    evaluated: the least inlier count of a new most-supported hypothesis or of a rival
    RivalMotions would keep, and the candidate set's front (which the set keeps). */
    void setBar(const SearchResult& result)
    {
        int least = result.mostSupportedInliers + 1;
        if (rivals_)
            least =
                std::min(least, rivals_->leastSupportConsidered(c_.scorer->ranksByInlierCount()));
        bar_.inliersThatMatter = least;
        bar_.front = &result.candidates.front();
    }

    void evaluate(int firstIteration, int count)
    {
        const bool sequential = !sequentialVerifiers_.empty();
        forEachIteration(count, [&](Lane& lane, int k) {
            IterationSlot& slot = slots_[static_cast<size_t>(k)];
            c_.sampler->generateSample(firstIteration + k, slot.sample);
            solveAndVerify(lane, slot, /*score=*/!sequential);
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
                    scoreHypothesis(lane, slot, h);
        });
    }

    void commit(IterationSlot& slot, CandidateSet& candidates, SearchResult& result)
    {
        if (slot.solutions == 0) {
            ++result.degenerateSamples;
            return;
        }
        result.hypotheses += static_cast<long long>(slot.models.size());
        pointsEvaluated_ += slot.pointsRead;
        for (size_t h = 0; h < slot.models.size(); ++h) {
            if (!slot.alive[h])
                continue;
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

    // Whether Params::maxIterations uniform samples fall short of the confidence bound for the
    // inlier ratio of `best`, at inner sampling's clean-sample success rate: a ratio that low is
    // where a loop selects a wrong motion, adaptive or not.
    bool budgetFallsShort(const CandidateSet::Candidate& best) const
    {
        const EstimatorComponents::InnerSampling& inner = c_.innerSampling;
        const double inlierRatio = static_cast<double>(best.score.inlierCount) / data_.size();
        const double cleanSample = std::pow(inlierRatio, static_cast<double>(innerDraw_.size()));
        return samplesForConfidence(inner.confidence, inner.successRate * cleanSample) >
               inner.maxIterations;
    }

    /* LO-RANSAC's inner sampling (Chum et al. 2003), with minimal samples, after a loop whose
    best candidate has an inlier ratio too low for its iteration budget (budgetFallsShort: the
    loop's clean samples are few, and those of a narrow view often fit a wrong motion): minimal
    samples drawn from the best candidate's inliers are committed like the loop's, in rounds,
    while they improve the best and its inlier ratio stays that low. A best of a wrong motion
    still holds mostly true inliers, so its inner samples are mostly clean where the loop's were
    not (w^m); minimal ones, because a fit to many of its inliers stays in its basin. Any other
    loop is left as it is. The draws depend only on (seed, draw count); SPRT does not see them,
    so its state is that of the loop. */
    void sampleInsideBest(CandidateSet& candidates, SearchResult& result)
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
                !budgetFallsShort(*best))
                return;
            source = best->score;
            c_.scorer->classify(data_, best->model, localInliers_);
            maskIndices(localInliers_, innerPool_);
            if (innerPool_.size() < 2 * m)
                return;
            for (int k = 0; k < inner.samplesPerRound; ++k) {
                uint64_t state = iterationState(~inner.seed, innerDrawn_++);
                drawDistinct(state, static_cast<uint32_t>(innerPool_.size()), 0, innerDraw_);
                for (size_t j = 0; j < m; ++j)
                    slot.sample[j] = innerPool_[static_cast<size_t>(innerDraw_[j])];
                setBar(result);
                solveAndVerify(lane, slot, /*score=*/true);
                commit(slot, candidates, result);
            }
        }
    }

    // The hypotheses of slot.sample, through the lane's verifiers (those before the first
    // sequential one) and, with `score`, evaluated by its scorer.
    void solveAndVerify(Lane& lane, IterationSlot& slot, bool score)
    {
        slot.solutions = lane.solver->estimate(data_, slot.sample, slot.models);
        slot.pointsRead = 0;
        for (size_t h = 0; h < slot.models.size(); ++h) {
            slot.bandInliers[h] = -1;
            slot.alive[h] = passes(lane.verifiers, slot, h);
            if (slot.alive[h] && score)
                scoreHypothesis(lane, slot, h);
        }
    }

    // A hypothesis whose band inliers a verifier has counted is not read again: a count below
    // bar_.inliersThatMatter then stays a candidate where the bail-out would have dropped it, which
    // changes nothing (it is neither the most supported, nor a rival, nor the best candidate).
    void scoreHypothesis(Lane& lane, IterationSlot& slot, size_t h) const
    {
        if (slot.bandInliers[h] >= 0)
            if (const std::optional<Score> counted =
                    lane.scorer->scoreOfBandCount(slot.bandInliers[h])) {
                slot.scores[h] = *counted;
                return;
            }
        int pointsRead = 0;
        slot.scores[h] = lane.scorer->evaluateUpTo(data_, slot.models[h], bar_, pointsRead);
        slot.pointsRead += pointsRead;
    }

    // The points a verifier checks are counted per slot, not read from the verifiers at the end:
    // a parallel run verifies iterations it does not commit, on copies of the verifiers.
    bool passes(const std::vector<ModelVerifier*>& verifiers, IterationSlot& slot, size_t h) const
    {
        for (ModelVerifier* verifier : verifiers) {
            const long long checkedBefore = verifier->pointsChecked();
            const bool isGood = verifier->isModelGood(data_, slot.sample, slot.models[h]);
            slot.pointsRead += verifier->pointsChecked() - checkedBefore;
            if (!isGood)
                return false;
            if (const int counted = verifier->bandInliersOfPassed(); counted >= 0)
                slot.bandInliers[h] = counted;
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
    std::unique_ptr<RivalMotions> rivals_;            //!< with components.tracksRivals only
    long long pointsEvaluated_ = 0; //!< residuals evaluated by verification and scoring
    HypothesisBar bar_;             //!< setBar() before the batch being evaluated
};

} // namespace

void searchHypotheses(const TwoViewData& data, EstimatorComponents& components,
                      SearchResult& result)
{
    HypothesisSearch(data, components).run(result);
}

} // namespace detail
} // namespace rcme
} // namespace cv
