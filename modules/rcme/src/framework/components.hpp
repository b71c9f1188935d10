// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP
#define OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP

// The component interfaces of rcme's RANSAC, shaped like OpenCV's USAC (calib3d/src/usac.hpp),
// which is private to calib3d and cannot be extended from outside. A method is a choice of one
// implementation per interface, assembled by estimator_factory.cpp and run by ransac_loop.cpp;
// each implementation lives in its own file under components/.

#include "framework/two_view_data.hpp"

namespace cv {
namespace rcme {
namespace detail {

//! One hypothesis (and, after selection, the estimate).
struct Model
{
    Eigen::Matrix3d F = Eigen::Matrix3d::Zero(); //!< pixel fundamental matrix, ||F|| = 1
    //! Set when the hypothesis is an essential matrix (calibrated data): F = K^-T E K^-1 up to
    //! scale. Otherwise zero, and the motion comes from F once a model is selected.
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
    //! Motion, valid when hasMotion: x2 = R x1 + t, |t| = 1.
    bool hasMotion = false;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    /** First-order uncertainty of the model: the covariance of its uncertaintyDof parameters
    theta (0: unknown; 5: the motion's tangent space, see MotionTangent; 7: F's, see
    FundamentalTangent) and the directions dF/dtheta_k in pixels, so that a residual's variance
    can be propagated without knowing the parameterization. Top-left block used. */
    int uncertaintyDof = 0;
    Eigen::Matrix<double, 7, 7> covariance = Eigen::Matrix<double, 7, 7>::Zero();
    Eigen::Matrix3d directions[7];
    //! Noise sigma estimated from the final inliers' residuals (Refiner::finalize), NaN if none.
    double noiseSigma = std::numeric_limits<double>::quiet_NaN();
};

/** Gives a model of calibrated data its motion: E (from F when the hypothesis was not
essential) is decomposed with cheirality on `inliers`, and E, F are set from (R, t). False when
no decomposition puts any inlier in front of both cameras. */
bool recoverMotion(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model);

/** The same from the points of a minimal sample alone (cheirality decided by them), with
`points1`, `points2` as buffers for the sample's points. */
bool recoverMotionFromSample(const TwoViewData& data, const std::vector<int>& sample, Model& model,
                             std::vector<Eigen::Vector2d>& points1,
                             std::vector<Eigen::Vector2d>& points2);

/** Whether two motions are different answers: their rotations differ by more than 5 deg or their
translation directions by more than 15 deg, the accuracy a right motion is held to
(doc/results.md). Both models must have their motion. */
bool areDistinctMotions(const Model& a, const Model& b);

//! Quality of a hypothesis as a scorer sees it; lower value is better.
struct Score
{
    double value = std::numeric_limits<double>::infinity();
    int inlierCount = 0;
    double meanEntropy = std::numeric_limits<double>::quiet_NaN();
    //! Whether the hypothesis passed the method's acceptance tests (may become the estimate).
    bool isCandidate = false;
    //! What the hypothesis tells the run-wide tests (RCME: its ratio of points in the noise-only
    //! band when it passes the quality test, else 0); read by Scorer::commit().
    double runEvidence = 0;

    bool isBetterThan(const Score& other) const { return value < other.value; }
};

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
    //! Whether the outcome depends on the hypotheses verified before (SPRT adapts its test):
    //! such a verifier, and every one after it, runs on one thread in iteration order.
    virtual bool isSequential() const { return false; }
    //! An independent copy (its own buffers) for another thread.
    virtual std::unique_ptr<ModelVerifier> clone() const = 0;
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
    the points the fit used. */
    virtual void finalize(const TwoViewData& data, std::vector<uchar>& inliers, Model& model) = 0;
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
    //! Evaluate hypotheses on several threads (Params::isParallel); the result is the same.
    bool parallel = false;
    //! cv::getTickCount() value at which the hypothesis loop stops (Params::timeBudget); 0: none.
    int64 deadline = 0;
    //! The final tests of a motion (calibrated data only; <= 0: off): Params::ambiguityMargin,
    //! Params::maxRotationStdDeg and Params::maxTranslationStdDeg.
    double ambiguityMargin = 0, maxRotationStdDeg = 0, maxTranslationStdDeg = 0;
};

/** The inlier count that chance alone exceeds with probability at most 5 % over a whole run: a
random correspondence falls within `threshold` (Sampson distance, pixels) of a hypothesis with
probability p, bounded generously by an epipolar band of half-width sqrt(2) * threshold across
the diagonal of the points' bounding box in image 2 over its area (the Sampson distance is at
least the image-2 line distance over sqrt(2)); the bound is the Binomial(n - m, p) quantile at
0.05 / maxIterations (Bonferroni over the hypotheses), plus the m sample points. A test of
non-randomness in the spirit of PROSAC's. */
int minimalSupport(const TwoViewData& data, double threshold, int sampleSize, int maxIterations);

// Factories of the component implementations, one file each under components/.
std::unique_ptr<Sampler> createUniformSampler(int pointCount, int sampleSize, uint64_t seed);
//! PROSAC over `order` (point indices, best first); order.size() >= sampleSize.
std::unique_ptr<Sampler> createProsacSampler(std::vector<int> order, int sampleSize, uint64_t seed);
//! With `essentialHypotheses` and calibrated data, hypotheses are projected onto the essential
//! manifold (E set); otherwise they are rank-2 F.
std::unique_ptr<MinimalSolver> createEightPointSolver(bool essentialHypotheses);
std::unique_ptr<Scorer> createInlierCountScorer(const TwoViewData& data, int sampleSize,
                                                int maxIterations);
// cleanSampleSuccessRate: Params::cleanSampleSuccessRate (1: the classic bound).
std::unique_ptr<Termination> createAdaptiveTermination(double confidence, int maxIterations,
                                                       int sampleSize,
                                                       double cleanSampleSuccessRate = 1.0);
std::unique_ptr<Termination> createExactTermination(int iterations);
std::unique_ptr<Refiner> createGoldStandardRefiner(int maxIterations);

//! 7-point solver for F (Hartley & Zisserman 11.1.2): up to three rank-2 F per sample, exact
//! (7 parameters for 7 DoF). With calibrated data the solutions are projected to E when
//! `essentialHypotheses` is set, like the 8-point solver.
std::unique_ptr<MinimalSolver> createSevenPointSolver(bool essentialHypotheses);
//! 5-point solver for E (Nister 2004, solvers/essential_five_point.cpp; calibrated data only):
//! up to ten essential matrices per sample, exact (5 parameters for 5 DoF), returned with model.E
//! and model.F set; those that cannot put the whole sample in front of both cameras are dropped.
std::unique_ptr<MinimalSolver> createFivePointSolver();
//! MLESAC's scorer (Torr & Zisserman 2000): negative log-likelihood of a Gaussian-inlier,
//! uniform-outlier mixture of the Sampson distances, mixing weight by a few EM steps.
std::unique_ptr<Scorer> createMlesacScorer(const TwoViewData& data, int sampleSize,
                                           int maxIterations);

//! SPRT (Matas & Chum 2005) on the propagated-uncertainty consistency test, adaptive epsilon and
//! delta (bound: data.consistencyBound); points in a fixed pseudo-random order from `seed`.
std::unique_ptr<ModelVerifier> createSprtVerifier(const TwoViewData& data, uint64_t seed);
//! The same SPRT on the threshold's Sampson band (the consistency of Standard and MLESAC).
std::unique_ptr<ModelVerifier> createBandSprtVerifier(const TwoViewData& data, uint64_t seed);
//! Cov-RANSAC's scorer: inliers by propagated uncertainty, most inliers wins.
std::unique_ptr<Scorer> createCovarianceInlierScorer(const TwoViewData& data, int sampleSize,
                                                     int maxIterations);

// RCME's boxes (doc/algorithm.md).
std::unique_ptr<MinimalSolver>
createUncertainModelInstantiation(std::unique_ptr<MinimalSolver> solver, int fitIterations);
//! Box 4 of Fig. 1(b): the sample's points against the hypothesis' propagated uncertainty.
std::unique_ptr<ModelVerifier> createModelSampleConsistencyTest(const TwoViewData& data,
                                                                bool leverage);
//! RCME's inlier-set quality test: the fields of Params with these names.
struct EntropyOptions
{
    double alpha;
    double entropyThreshold;
    double inlierRatioFactor;
    double priorInlierRatio;
};
EntropyOptions entropyOptions(const Params& params);
std::unique_ptr<Scorer> createEntropyScorer(const TwoViewData& data, const EntropyOptions& options,
                                            int sampleSize, int maxIterations);
//! Stops once the best candidate's mean entropy is at most entropyBound (> 0), else as `bound`.
std::unique_ptr<Termination> createEntropyTermination(std::unique_ptr<Termination> bound,
                                                      double entropyBound);

//! The final inliers compared with a homography (components/homography_comparison.cpp).
struct HomographyComparison
{
    double fundamentalGric = 0.0;
    double homographyGric = 0.0;
    //! A homography explains the inliers at least as well as F: planar scene or pure rotation.
    bool homographyExplainsInliers = false;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero(); //!< the homography (pixels), when fitted
};
/** Torr's GRIC of F and of a homography fitted (RANSAC) to the method's inliers `mask` and F's
support (the points within data.threshold of it), over the points either model explains, with
the noise of the homography's inliers (at most data.sigma); with fewer than 8 points or no
homography, nothing is flagged. */
HomographyComparison compareWithHomography(const TwoViewData& data, const Eigen::Matrix3d& F,
                                           const std::vector<uchar>& mask);

//! With K, the inliers against a rotation about the camera centre (x2 ~ K R K^-1 x1).
struct RotationComparison
{
    double rotationGric = 0.0;
    double motionGric = 0.0;
    //! The rotation explains the inliers at least as well as the motion: no translation seen.
    bool rotationExplainsInliers = false;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    //! sigma^2 (J^T J)^-1 of the rotation increment omega, R exp([omega]x), when determined.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    bool hasCovariance = false;
    std::vector<uchar> inliers; //!< the points the rotation explains (2-DoF chi-square, 95 %)
};
/** Fits a rotation to the inliers `mask` (Procrustes on the viewing rays, then Gauss-Newton on
the homography Sampson error) and compares it with the motion of F by Torr's GRIC (rotation:
manifold dimension 2, 3 parameters; motion: 3 and 5), as compareWithHomography does. Calibrated
data only. */
RotationComparison compareWithRotation(const TwoViewData& data, const Eigen::Matrix3d& F,
                                       const std::vector<uchar>& mask);
//! The motions (R, unit t) of cv::decomposeHomographyMat(H, K), as models with E and F set;
//! decompositions without translation are left out. Calibrated data only.
std::vector<Model> homographyMotions(const TwoViewData& data, const Eigen::Matrix3d& H);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_COMPONENTS_HPP
