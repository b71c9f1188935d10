// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP
#define OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP

// The component interfaces of rcme's RANSAC, shaped like OpenCV's USAC (calib3d/src/usac.hpp),
// which is private to calib3d and cannot be extended from outside. A method is a choice of one
// implementation per interface, assembled by estimator_factory.cpp and run by ransac_loop.cpp;
// each implementation lives in its own file under components/.

#include "framework/estimate.hpp"

#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace cv {
namespace rcme {
namespace detail {

//! Draws minimal samples. Sample j depends only on (seed, j), so runs are reproducible and
//! iterations can be evaluated in any order, on any thread.
class Sampler
{
public:
    virtual ~Sampler() = default;
    //! Fills `sample` (size = sample size) with distinct indices for iteration `iteration`.
    //! Thread-safe.
    virtual void generateSample(int iteration, std::vector<int>& sample) const = 0;
};

//! Instantiates hypotheses from a minimal sample.
class MinimalSolver
{
public:
    virtual ~MinimalSolver() = default;
    virtual int sampleSize() const = 0;
    virtual int maxSolutions() const = 0;
    //! More parameters than the model has degrees of freedom (the paper's consistency test
    //! applies only then).
    virtual bool isOverParameterized() const = 0;
    //! Appends the hypotheses of `sample` to `models` (cleared first); returns how many. Zero
    //! means the sample is degenerate.
    virtual int estimate(const TwoViewData& data, const std::vector<int>& sample,
                         std::vector<Model>& models) = 0;
    //! An independent copy (its own buffers) for another thread.
    virtual std::unique_ptr<MinimalSolver> clone() const = 0;
};

//! Tests a hypothesis before it is scored (model-sample consistency, SPRT, ...).
class ModelVerifier
{
public:
    virtual ~ModelVerifier() = default;
    //! May complete the model (e.g. its covariance). False drops it.
    virtual bool isModelGood(const TwoViewData& data, const std::vector<int>& sample,
                             Model& model) = 0;
    //! Correspondences (outside the sample) whose residual this verifier evaluated so far: the
    //! cost SPRT saves is reported from it.
    virtual long long pointsChecked() const { return 0; }
    //! After isModelGood() passed a model: its number of points within the threshold's Sampson
    //! band when the verifier counted them on every point (SPRT on the band), else -1.
    virtual int bandInliersOfPassed() const { return -1; }
    //! Whether the outcome depends on the hypotheses verified before (SPRT adapts its test):
    //! such a verifier, and every one after it, runs on one thread in iteration order.
    virtual bool isSequential() const { return false; }
    //! An independent copy (its own buffers) for another thread.
    virtual std::unique_ptr<ModelVerifier> clone() const = 0;
};

/** What the candidate set refuses (CandidateSet keeps it and decides by it): its members as steps
of (score value, most inliers among the members of at most that value), values increasing. A
hypothesis of value v and n inliers is refused when some member is at least as good in both,
that is when mostInliersAtOrBelow(v) >= n. */
struct CandidateFront
{
    std::vector<std::pair<double, int>> steps;

    //! The most inliers of a member whose value is at most `value`, or -1 if there is none (a
    //! NaN value is beaten by no member).
    int mostInliersAtOrBelow(double value) const
    {
        int most = -1;
        for (const auto& [stepValue, inliers] : steps) {
            if (!(stepValue <= value))
                break;
            most = inliers;
        }
        return most;
    }
};

/** What a hypothesis of the loop must reach to change the run (HypothesisSearch), set before a
batch of hypotheses is evaluated; read by Scorer::evaluateUpTo to stop reading a hypothesis that
cannot. Nothing is committed while a batch is evaluated, and both only tighten as it is, so a
hypothesis out of reach then stays so. */
struct HypothesisBar
{
    //! The inlier count from which a hypothesis matters by its count alone: a new most-supported
    //! hypothesis, or a rival the ambiguity test would keep.
    int inliersThatMatter = 0;
    //! The candidate set's front (null: none given), for a scorer that ranks by another score.
    const CandidateFront* front = nullptr;
};

/** Scores hypotheses and classifies points. A score is computed in two steps so that hypotheses
can be evaluated on several threads with the result of a sequential run: evaluate() depends only
on the model (any thread, its own copy of the scorer), commit() feeds the run-wide state and
settles what depends on it (called in iteration order, on the loop's scorer). */
class Scorer
{
public:
    virtual ~Scorer() = default;
    //! The score of `model` before the run-wide tests; uses only this scorer's buffers.
    virtual Score evaluate(const TwoViewData& data, const Model& model) = 0;
    /** evaluate() for the loop's hypotheses, which matter to the run only when they reach `bar`
    (a new most-supported hypothesis, a rival the ambiguity test keeps, or a candidate the
    candidate set takes). A scorer may stop reading points once the hypothesis is out of reach
    (early bail-out, as USAC's and COLMAP's): it then returns an inlier count below
    bar.inliersThatMatter and no candidate, and the run is the same as with every point read.
    `pointsRead` receives the number of points read. By default every point is read. */
    virtual Score evaluateUpTo(const TwoViewData& data, const Model& model,
                               const HypothesisBar& bar, int& pointsRead)
    {
        (void)bar;
        pointsRead = data.size();
        return evaluate(data, model);
    }
    /** The score evaluate() gives a model with `bandInliers` points within the threshold's
    Sampson band, when that count is all it needs (a scorer that counts the band's inliers: a
    verifier that counted them spares it a second pass); std::nullopt otherwise. */
    virtual std::optional<Score> scoreOfBandCount(int bandInliers) const
    {
        (void)bandInliers;
        return std::nullopt;
    }
    //! Whether Score::value is minus the inlier count (a better score is a larger count).
    virtual bool ranksByInlierCount() const { return false; }
    //! Records an evaluated score in the run so far and completes `score.isCandidate`.
    virtual void commit(Score& score) { (void)score; }
    //! evaluate() then commit(): the score of `model` in a sequential run.
    Score score(const TwoViewData& data, const Model& model)
    {
        Score result = evaluate(data, model);
        commit(result);
        return result;
    }
    //! An independent copy (its own buffers) for another thread, to call evaluate() on.
    virtual std::unique_ptr<Scorer> clone() const = 0;
    //! Writes 1 for the inliers of `model`, 0 otherwise; `mask` is resized to data.size().
    virtual void classify(const TwoViewData& data, const Model& model,
                          std::vector<uchar>& mask) = 0;
    //! Whether a candidate still passes the tests that depend on the whole run so far (RCME's
    //! size test against the estimated inlier ratio, which only grows).
    virtual bool isStillCandidate(const Score&) const { return true; }
    //! Whether the refinement (box 4) of a selected model is kept: by default when it is still a
    //! candidate and scores at least as well as before.
    virtual bool keepsRefinement(const Score& before, const Score& refined) const
    {
        return refined.isCandidate && !before.isBetterThan(refined);
    }
};

//! Decides how many iterations to run.
class Termination
{
public:
    virtual ~Termination() = default;
    //! Iterations to run given what has been seen so far.
    virtual int iterationBound() const = 0;
    //! Called each time a new best candidate is found.
    virtual void update(const Score& best, int pointCount) = 0;
};

//! Whether the final fit moves the model (Refiner::finalize).
enum class FinalModel
{
    kFitted, //!< least squares on the inliers moves it
    kHeld    //!< it stays as it is; only its inliers and uncertainty are computed there
};

//! Refines the selected hypothesis on its inliers.
class Refiner
{
public:
    virtual ~Refiner() = default;
    //! Returns false (model untouched) when refinement is not possible.
    virtual bool refine(const TwoViewData& data, const std::vector<uchar>& inliers,
                        Model& model) = 0;
    /** The estimate's final fit and uncertainty, once: on the inliers in front of both cameras
    (calibrated) that the others confirm, with the noise estimated from their residuals and the
    covariance of the band-truncated fit (see Report::covariance). On return `inliers` marks
    the points the fit used. With FinalModel::kHeld the model is not moved (no iterations). */
    virtual void finalize(const TwoViewData& data, std::vector<uchar>& inliers, Model& model,
                          FinalModel kind) = 0;
};

struct SearchResult;
class ModelSpace;
class Refinement;

//! What a stage after the loop may read: the data, what the loop found, and the method's scorer,
//! refinement and model space.
struct StageContext
{
    const TwoViewData& data;
    const SearchResult& search;
    Scorer& scorer;
    const Refinement& refinement;
    const ModelSpace& space;
};

/** A stage after the loop, in the order of the paper's Fig. 1: selection, refinement, the
decisions on what the data determine (OpenCV USAC's Degeneracy kind), the final fit. It reads
the estimate as it stands and returns what it found (a model, a verdict with its reason, a
measure); the pipeline (framework/estimation_pipeline.cpp) applies it. */
class EstimationStage
{
public:
    virtual ~EstimationStage() = default;
    //! Whether it runs on an estimate an earlier stage turned down (by default it does not).
    virtual bool runsOnFailure() const { return false; }
    virtual StageOutcome run(const StageContext& context, const Estimate& estimate) = 0;
};

//! A method: one component of each kind.
struct EstimatorComponents
{
    std::unique_ptr<Sampler> sampler;
    std::unique_ptr<MinimalSolver> solver;
    std::vector<std::unique_ptr<ModelVerifier>> verifiers; //!< applied in order, may be empty
    std::unique_ptr<Scorer> scorer;
    std::unique_ptr<Termination> termination;
    std::unique_ptr<Refiner> refiner; //!< null when refinement is off
    //! Refits new candidates on their inliers (LO-RANSAC); null when local optimisation is off.
    std::unique_ptr<Refiner> localOptimizer;
    /** LO-RANSAC's inner sampling, for a loop whose best candidate's inlier ratio is too low for
    its iteration budget: minimal samples drawn from the inliers of the best candidate
    (ransac_loop.cpp). */
    struct InnerSampling
    {
        int samplesPerRound = 0; //!< 0: off
        //! It runs when maxIterations samples fall short of log(1 - confidence) /
        //! log(1 - successRate w^m) for the best candidate's inlier ratio w (Params::confidence,
        //! Params::maxIterations, a success rate of clean samples at most Params'
        //! cleanSampleSuccessRate).
        double confidence = 0.99;
        double successRate = 1.0;
        int maxIterations = 0;
        uint64_t seed = 0; //!< Params::randomGeneratorState
    } innerSampling;
    //! Evaluate hypotheses on several threads (Params::isParallel); the result is the same.
    bool parallel = false;
    //! cv::getTickCount() value at which the hypothesis loop stops (Params::timeBudget); 0: none.
    int64 deadline = 0;
    //! What an estimate is: F, or with K the motion (framework/model_space.hpp). Shared, as the
    //! components that lift hypotheses hold it too.
    std::shared_ptr<const ModelSpace> space;
    //! The stages after the loop, in order (framework/estimation_pipeline.cpp).
    std::vector<std::unique_ptr<EstimationStage>> stages;
    //! The loop remembers the distinct motions among its candidates (RivalMotions), for a stage
    //! that weighs them (the rival motion decision).
    bool tracksRivals = false;
};

/** The probability p that a random correspondence falls within `threshold` (Sampson distance,
pixels) of a given F, bounded generously by an epipolar band of half-width sqrt(2) * threshold
across the diagonal of the points' bounding box in image 2 over its area (the Sampson distance is
at least the image-2 line distance over sqrt(2)). */
double chanceOfBand(const TwoViewData& data, double threshold);

/** The inlier count that chance alone exceeds with probability at most 5 % over a whole run: the
Binomial(n - m, p) quantile at 0.05 / maxIterations (Bonferroni over the hypotheses; p:
chanceOfBand), plus the m sample points. A test of non-randomness in the spirit of PROSAC's. */
int minimalSupport(const TwoViewData& data, double threshold, int sampleSize, int maxIterations);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP
