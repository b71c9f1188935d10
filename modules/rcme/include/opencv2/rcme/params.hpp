// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_PARAMS_HPP
#define OPENCV_RCME_PARAMS_HPP

#include "opencv2/rcme/opencv_geometry.hpp"

namespace cv {
namespace rcme {

//! @addtogroup rcme
//! @{

/** @brief Robust estimation method.

The values do not collide with OpenCV's own method flags, so they can be passed as the `method`
argument of the drop-in overloads (where cv::FM_RANSAC and cv::RANSAC select #METHOD_STANDARD).

The enums of the module have `int` as their fixed underlying type, so that any integer (from
Python, a file, a cast) is a value the argument checks can reject with a message; without it, a
value outside an enum's range would be undefined behaviour before any check could run.
*/
enum Method
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    METHOD_RCME = 1024,  //!< model quality aware RANSAC @cite Yeh2021RCME
    METHOD_PRCME = 1025, //!< RCME without the model-sample consistency test
    METHOD_STANDARD =
        1026,             //!< Gold Standard: RANSAC, inlier count, MLE refinement @cite Hartley2004
    METHOD_MLESAC = 1027, //!< MLESAC @cite Torr2000MLESAC
    METHOD_COV_RANSAC = 1028 //!< Cov-RANSAC with SPRT @cite Raguram2009CovRANSAC
};

//! How minimal samples are drawn.
enum SamplerKind
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    SAMPLER_UNIFORM = 0, //!< every subset equally likely @cite Fischler1981
    SAMPLER_PROSAC = 1   //!< progressive sampling by match quality @cite Chum2005PROSAC
};

//! Which minimal solver instantiates the hypotheses.
enum MinimalSolverKind
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    SOLVER_EIGHT_POINT = 0, //!< normalized 8-point @cite Hartley2004 (over-parameterized)
    SOLVER_SEVEN_POINT = 1, //!< 7-point, up to three F (exact)
    SOLVER_FIVE_POINT = 2,  //!< 5-point, up to ten E (exact, needs the camera matrix)
    /** the 5-point solver when a camera matrix is given, the 7-point one otherwise: with K the
    5-point solver returned the fewest wrong motions of the three (doc/results.md), without K the
    7-point one more right F than the 8-point one (doc/f_only.md) */
    SOLVER_AUTO = 3
};

/** How much of the data a hypothesis is verified on before it is scored. */
enum VerificationKind
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    /** SPRT for #METHOD_COV_RANSAC (part of the method) and, for every method, from 20000
    correspondences on; below that every hypothesis is scored on every point */
    VERIFICATION_AUTO = 0,
    VERIFICATION_NONE = 1, //!< every hypothesis is scored on every point (Cov-RANSAC too)
    /** Wald's sequential probability ratio test @cite Matas2005SPRT before scoring: the points
    are checked in a fixed random order and a hypothesis is dropped as soon as its consistent
    share is unlikely for a good model. Consistency is the method's inlier test: the propagated
    uncertainty for the RCME family and Cov-RANSAC, the threshold's band for Standard and
    MLESAC. A good hypothesis is dropped with a small probability, so results differ from
    #VERIFICATION_NONE's */
    VERIFICATION_SPRT = 2
};

/** How #METHOD_STANDARD ranks its hypotheses (the other methods have their own quality and
ignore Params::scoring). */
enum ScoringKind
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    /** the inlier count with a camera matrix, the truncated cost without one: without K the
    truncated cost gave more right F on the synthetic hard cases, and no change on the real
    pairs (doc/f_only.md) */
    SCORING_AUTO = 0,
    SCORING_INLIER_COUNT = 1, //!< the points within the threshold's Sampson band (the paper's)
    /** MSAC's truncated cost @cite Torr2000MLESAC over the squared Sampson distances, each capped
    at 1.5 thresholds, so that a hypothesis whose true matches lie just outside the band is not
    outranked by one holding a few more points inside it. The candidate test and the inliers
    are the band's, as with the count */
    SCORING_TRUNCATED_COST = 2
};

/** @brief Outcome of an estimation. Every estimating function reports one.

Only #STATUS_SUCCESS comes with a model, and #STATUS_PURE_ROTATION with a rotation; with any
other status the returned matrices are empty and the mask is all zeros.

How often each status is right against ground truth is measured in doc/results.md ("Statuses
against ground truth").
*/
enum Status
#ifndef OPENCV_BINDING_PARSER // OpenCV 4.6's binding generator cannot read an enum base
    : int
#endif
{
    STATUS_SUCCESS = 0, //!< a model was found and is returned
    /** no hypothesis passed the method's acceptance tests: for RCME the inlier-set quality and
    size tests, for every method a support no larger than chance would give (with a camera
    matrix also the final motion's inliers against the share of random pairings of these points
    that its epipolar band holds). The input is too poor to trust any motion from it (the
    paper's PQI). */
    STATUS_POOR_QUALITY_INPUT = 1,
    STATUS_NOT_ENOUGH_POINTS = 2, //!< fewer valid correspondences than the minimal solver needs
    /** every sample, or the selected model, was degenerate: points identical or collinear; a
    planar scene or a pure rotation without a camera matrix (F is then not determined); with
    one, a planar scene whose two motions cheirality cannot tell apart, or a motion that
    cheirality cannot resolve. A planar scene with a camera matrix is otherwise a success. */
    STATUS_DEGENERATE_CONFIGURATION = 3,
    /** with a camera matrix, a rotation about the camera centre explains the inliers as well as
    a motion (Torr's GRIC): R is returned, t is zero (not determined), E and F are empty, and the
    covariance is the 3x3 one of the rotation increment. The mask marks the points the rotation
    explains. */
    STATUS_PURE_ROTATION = 4,
    /** with a camera matrix, the inliers do not determine the motion to the accuracy asked: a
    distinct motion (rotation more than 5 deg or translation direction more than 15 deg away)
    explains them about as well (Params::ambiguityMargin), or the motion's propagated standard
    deviation exceeds Params::maxRotationStdDeg or Params::maxTranslationStdDeg, or (with
    maxTranslationStdDeg > 0) the points that move beyond the threshold once the rotation is
    removed lie on the motion's epipolar lines no more often than random directions of their
    motion would (a camera standing still: the translation is not determined). The motion
    turned down is in Report::rejectedR, rejectedT. */
    STATUS_UNDETERMINED_MOTION = 5
};

/** @brief Parameters of the robust estimators, shaped like cv::UsacParams.

Every field has a documented default; a default-constructed Params runs the Standard estimator
with noise sigma 1 px, the 5-point solver when a camera matrix is given (the 7-point one
otherwise), local optimisation and the ambiguity and uncertainty tests; asPublished() gives a
method as the paper ran it. Construct from cv::UsacParams to carry over the fields the two share.
*/
struct CV_EXPORTS_W_SIMPLE Params
{
    //! Sets every field to its documented default.
    CV_WRAP Params();
    /** @brief Carries over the fields shared with cv::UsacParams: confidence, maxIterations,
    randomGeneratorState, threshold, isParallel, and sampler (uniform or PROSAC). The other USAC
    fields (score, local optimisation, neighbourhoods) have no counterpart and are ignored;
    NAPSAC samplers raise cv::Error::StsBadArg.

    Not wrapped for Python: OpenCV's generator (4.6) turns an exception thrown by a constructor
    of a simple struct into a SystemError without its message; Python uses fromUsacParams. */
    explicit Params(const UsacParams& usacParams);
    /** @brief The same as Params(const UsacParams&), for Python:
    `cv2.rcme.Params.fromUsacParams(u)` (also `cv2.rcme.Params_fromUsacParams(u)`). */
    CV_WRAP static Params fromUsacParams(const UsacParams& usacParams);
    /** @brief The configuration of the paper's experiments for @p method: the defaults but for
    the 8-point solver, no local optimisation, neither the ambiguity nor the uncertainty test, and
    the classic adaptive bound (cleanSampleSuccessRate 1).
    The defaults differ where measurement found them better (doc/results.md). */
    CV_WRAP static Params asPublished(Method method);

    //! Robust method. Default #METHOD_STANDARD.
    CV_PROP_RW Method method;
    //! Sampler. Default #SAMPLER_UNIFORM.
    CV_PROP_RW SamplerKind sampler;
    //! Minimal solver. Default #SOLVER_AUTO (the paper's experiments: #SOLVER_EIGHT_POINT).
    CV_PROP_RW MinimalSolverKind solver;
    /** Verification before scoring. Default #VERIFICATION_AUTO: SPRT for Cov-RANSAC and on
    large inputs (from 20000 correspondences), where scoring every point of every hypothesis
    dominates the time (doc/performance.md, "Large inputs"). */
    CV_PROP_RW VerificationKind verification;
    /** How #METHOD_STANDARD ranks hypotheses; the other methods rank by their own quality and
    ignore it. Default #SCORING_AUTO (asPublished: #SCORING_INLIER_COUNT). */
    CV_PROP_RW ScoringKind scoring;
    //! Standard deviation of the point noise, pixels per coordinate (assumption a.2). Default 1.
    CV_PROP_RW double sigma;
    /** Inlier threshold on the Sampson distance to the epipolar geometry, pixels. When <= 0
    (default) it is derived from sigma: sigma * sqrt(chi2_1^-1(0.95)) = 1.96 sigma. */
    CV_PROP_RW double threshold;
    //! Confidence of the adaptive iteration bound, in (0, 1). Default 0.99.
    CV_PROP_RW double confidence;
    /** Fraction q of all-inlier samples assumed to give a hypothesis of the right motion, in
    (0, 1], or 0: the adaptive bound is N = log(1 - confidence) / log(1 - q w^m). 1 is the
    classic bound (asPublished). With a camera matrix, a clean minimal sample of noisy points
    seen by a narrow field of view often fits a wrong motion, so the classic bound stops too
    early (doc/results.md); without one the extra samples changed no status of the F-only
    suites (doc/f_only.md). Default 0: 0.3 with a camera matrix, 1 without. */
    CV_PROP_RW double cleanSampleSuccessRate;
    /** Maximum number of iterations (hypothesis draws), in [1, 10^7] (OpenCV's forms clamp
    their maxIters into that range). Default 1000. */
    CV_PROP_RW int maxIterations;
    //! Run exactly maxIterations iterations, as in the paper's experiments. Default false.
    CV_PROP_RW bool exactIterations;
    //! Seed of the random generator; the same seed gives the same result. Default 0.
    CV_PROP_RW int randomGeneratorState;
    //! Refine the selected model by Gold Standard MLE on its inliers. Default true.
    CV_PROP_RW bool refine;
    //! Maximum Levenberg-Marquardt iterations of the refinement. Default 20.
    CV_PROP_RW int refineIterations;
    /** Noise of Report::covariance: true (default) uses Report::noiseSigma, the noise estimated
    from the final inliers' residuals, when they leave at least 30 residual degrees of freedom
    (inliers minus the model's 5 or 7) and the stated sigma otherwise; with a camera matrix the
    reported covariance then takes the posterior noise at every count instead, the estimate shrunk
    toward the stated sigma (see Report::covariance). false always uses the stated sigma. The
    estimate does not change the inlier threshold, only the covariance. */
    CV_PROP_RW bool useEstimatedNoise;
    //! Significance level of RCME's tests (consistency and quality). Default 0.05.
    CV_PROP_RW double alpha;
    /** RCME's entropy threshold mu, as the excess of the mean inlier entropy over the noise
    floor 1/2 log(2 pi e sigma^2), in nats; unit-free, so it keeps its meaning whatever the image
    size or focal length. The paper's mu = -3.53 (f = 500 px, sigma = 1 px) is 1.27. */
    CV_PROP_RW double entropyThreshold;
    /** RCME's conservative coefficient lambda of the size test n_j/n >= lambda * omega_p; the paper
    allows [0.5, 1]. Default 0.9 (measured on the corridor, doc/results.md). */
    CV_PROP_RW double inlierRatioFactor;
    //! RCME's prior inlier ratio omega_p in (0, 1]; <= 0 (default) estimates it during the run.
    CV_PROP_RW double priorInlierRatio;
    //! Degrees of freedom of RCME's chi-square tests on the Sampson error (paper: 3). Default 1.
    CV_PROP_RW int consistencyDof;
    /** RCME: Gauss-Newton iterations fitting each hypothesis to its own minimal sample before its
    covariance is computed; 0 keeps the solver's output, as the paper. Default 5: with 0, the
    essential matrix projected from an 8-point F rarely fits its own sample and the consistency
    test rejects most corridor scenes (doc/experiments_archive.md). */
    CV_PROP_RW int sampleFitIterations;
    /** RCME's consistency test: give the samples the leverage-corrected variance
    sigma^2 - g Sigma g^T (they built the model) instead of the paper's sigma^2 + g Sigma g^T. */
    CV_PROP_RW bool sampleLeverage;
    /** RCME's early termination: stop once a candidate's mean excess entropy is at most this
    (nats, as entropyThreshold); <= 0 disables it. Ignored when exactIterations is set. */
    CV_PROP_RW double earlyTerminationEntropy;
    /** Local optimisation (LO-RANSAC @cite Chum2003LORANSAC): each hypothesis that enters the
    candidate set is refitted on its inliers (a few Gauss-Newton steps) and the refit competes as
    a candidate too. When maxIterations samples fall short of the confidence bound
    log(1 - confidence) / log(1 - q w^m) for the best candidate's inlier ratio w, with q the
    smaller of cleanSampleSuccessRate (as applied) and 0.1 (an inlier ratio below about 0.55 with
    1000 5-point samples, adaptive or not), minimal samples drawn from the best candidate's inliers
    (LO-RANSAC's inner sampling; 100 per round, up to 4 rounds while they improve it) compete
    too: a wrong motion's inliers are mostly true ones, so they find the true motion that the
    loop's few clean samples missed (doc/results.md). Other loops are not changed. With a camera
    matrix and refine, the returned motion is then polished once its status is decided: refitted
    on its inliers with a Cauchy loss (scale a quarter of threshold), as PoseLib's last step,
    when its residuals say that is more precise than least squares (their tails are wider than a
    Gaussian's, as real matches' are); no status depends on it (doc/results.md, "The final
    polish"). Default true (the paper's experiments: false). */
    CV_PROP_RW bool localOptimization;
    /** After the loop, compare the final inliers' fit by F with their fit by a homography
    (Torr's GRIC @cite Torr1998GRIC). When the homography explains them at least as well (a planar
    scene, a rotation without translation, too little parallax): without a camera matrix only the
    correspondences off the homography's plane can fix F = [e']x H (plane and parallax): F stands,
    or is replaced by the F of the epipole most of them agree with, when more of them agree with
    one epipole than chance alignments explain, and otherwise the status is
    #STATUS_DEGENERATE_CONFIGURATION (the message gives the counts); with one, a rotation that
    explains them as well as a motion gives #STATUS_PURE_ROTATION, and otherwise the motion of
    the plane is taken from E or from the homography's decomposition, whichever puts the most
    inliers in front of both cameras (degenerate when two motions do and fit them within 10
    sigma^2 of cost). Default true. */
    CV_PROP_RW bool degeneracyTest;
    /** The ambiguity test, with a camera matrix: the loop remembers the best hypothesis of each
    distinct motion it saw; after it, those with at least half the selected model's support and
    a truncated cost at most 0.6 sigma^2 per point above the selected model's as they stand (a
    costlier one does not come within the margin when refitted) are refitted on the points they
    explain, the one of least truncated cost (MSAC, a point behind a camera costing as an
    outlier) is returned, and when a distinct motion's cost is within this many sigma^2 of it
    (Report::rivalCostGap, twice a log-likelihood ratio) the status is
    #STATUS_UNDETERMINED_MOTION. After it (and on a planar scene's motion, which it leaves to
    the degeneracy test) the same rivals are weighed at the noise the final fit measured when
    that is below sigma: MSAC's cost capped at the threshold scaled by measured / stated noise, and
    a rival cheaper by 10 measured sigma^2 (on a plane's motion: that also fits its own points at
    most at 0.75 of the estimate's noise) replaces the estimate, with its own final fit
    (rivalCostGap stays the first comparison's). A threshold wider than the noise otherwise lets
    a motion win with points a few noise widths off its epipolar lines (KITTI 01's consecutive
    KLT pairs, doc/vo_front_end.md). <= 0 disables both (the rivals are then neither refitted
    nor compared). Default 2, chosen on synthetic scenes (doc/experiments_archive.md); the
    paper's experiments: 0. */
    CV_PROP_RW double ambiguityMargin;
    /** The uncertainty test, with a camera matrix and refinement: a motion whose rotation
    standard deviation about an axis (Report::rotationStdDeg) exceeds this many degrees gives
    #STATUS_UNDETERMINED_MOTION. <= 0 disables it. Default 4 deg, chosen with inner sampling's
    trigger on synthetic scenes (doc/experiments_archive.md); the paper's experiments: 0. The
    bound applies to the model-based standard deviation, before Report::covariance is raised to
    the residuals' sandwich, so a success's Report::rotationStdDeg can exceed it. Its noise is the
    final fit's: below 35 inliers the stated sigma, unless (with useEstimatedNoise) the inliers'
    residuals rule it out at the 1 % level, then the largest noise they do not rule out,
    noiseSigma sqrt(nu / chi2_nu(0.01)) with nu = inliers - 5 (a few precise inliers are not
    flagged for a sigma they contradict). */
    CV_PROP_RW double maxRotationStdDeg;
    /** The same for the translation direction (Report::translationStdDeg), degrees. <= 0
    disables it, and with it the test that the moving points determine the translation
    (#STATUS_UNDETERMINED_MOTION). Default 8 deg, chosen with maxRotationStdDeg; the paper's
    experiments: 0. As maxRotationStdDeg, it bounds the model-based standard deviation, at the
    same noise. */
    CV_PROP_RW double maxTranslationStdDeg;
    /** For #SAMPLER_PROSAC: one score per correspondence, higher is better (e.g. the negated
    ratio of the two best descriptor distances), CV_32F or CV_64F. Empty (default): the points
    are taken as already sorted by decreasing quality, as OpenCV's USAC PROSAC assumes. */
    CV_PROP_RW Mat matchQuality;
    /** Evaluate hypotheses on OpenCV's threads (cv::parallel_for_, as many as
    cv::getNumThreads()), in batches of 64 iterations. The result is the same as without it, for
    every method and whatever the thread count: sample j depends only on (seed, j), and what
    depends on earlier hypotheses (candidate set, ties, iteration bound, RCME's size test, SPRT)
    is decided in iteration order. Default false. */
    CV_PROP_RW bool isParallel;
    /** Wall-time budget of one call, in seconds; <= 0 (default): none. When it runs out the
    hypothesis loop stops and the best model found so far goes on to refinement and the final
    tests, so the status says whether it can be trusted (#STATUS_POOR_QUALITY_INPUT when there
    is none, with a message saying the budget ran out). Refinement and the final tests are not
    cut short, so a call can overrun the budget by their time (milliseconds). */
    CV_PROP_RW double timeBudget;
};

/** @brief Everything an estimation produced, for callers who want more than the model.

Matrices are CV_64F; all but mask and the rejected* diagnostics are empty unless status is
#STATUS_SUCCESS.
*/
struct CV_EXPORTS_W_SIMPLE Report
{
    //! An empty report: status #STATUS_POOR_QUALITY_INPUT, no model, NaN mean entropy.
    CV_WRAP Report();
    CV_PROP_RW Status status;   //!< outcome; the models below are set only on success
    CV_PROP_RW String message;  //!< why the status is not #STATUS_SUCCESS, empty otherwise
    CV_PROP_RW Mat F;           //!< 3x3 fundamental matrix (pixels), ||F|| = 1
    CV_PROP_RW Mat E;           //!< 3x3 essential matrix, only with a camera matrix
    CV_PROP_RW Mat R;           //!< 3x3 rotation, only with a camera matrix
    CV_PROP_RW Mat t;           //!< 3x1 unit translation, only with a camera matrix
    CV_PROP_RW Mat mask;        //!< Nx1 CV_8U inlier mask, 0 or 1, always sized
    CV_PROP_RW int inlierCount; //!< number of ones in mask
    CV_PROP_RW int iterations;  //!< samples drawn by the loop (not local optimisation's inner ones)
    /** Mean number of correspondences whose residual was evaluated per hypothesis, in
    verification and scoring: the number of points for methods that score every hypothesis on
    all of them, fewer with SPRT (Params::verification; always with Cov-RANSAC), which rejects
    bad hypotheses after a few points, and with METHOD_STANDARD, whose inlier count stops once a
    hypothesis cannot beat the best one (early bail-out, which changes no result) and which with
    SPRT takes the count of a hypothesis SPRT passed from SPRT's own reading. With
    isParallel hypotheses are evaluated in batches before the best one of the batch is known, so
    this can be higher than in a sequential run (the same for every thread count). NaN when no
    hypothesis was instantiated. */
    CV_PROP_RW double pointsPerHypothesis;
    CV_PROP_RW double meanEntropy; //!< RCME's mean inlier entropy psi (nats), NaN for other methods
    /** 5x5 covariance of the motion in the tangent space (rotation increment omega, rad, then
    the two components of the translation direction increment in an orthonormal basis of t's
    complement), only with a camera matrix; empty when refinement is off. R_true = R exp([omega]x)
    and t_true ~ t + B beta, where B's columns are b1 = normalize(t x e_k) (e_k the axis of t's
    smallest absolute component) and b2 = t x b1. It is the first-order covariance of the Gold
    Standard fit on the points inside the band of that fit itself (the band is taken again after
    each fit, up to four times, until it no longer changes), in front of both cameras, and
    confirmed by the others (leverage <= 1/2 in the fit on all of them, studentized residual inside
    the band; the mask marks them; a point left alone in a direction may then hold more): sigma^2 /
    h(c / sigma) (J^T J)^-1, at the returned motion (after the final polish of
    Params::localOptimization, when it applies), with sigma the noise chosen by
    Params::useEstimatedNoise, c the inlier threshold and h(k) = E[z^2 | |z| < k] (the fit sees
    only residuals inside the band; 1 / h = 1.32 at 1.96 sigma).
    With the estimated noise, sigma^2 is then the posterior (4 s0^2 + nu s^2) / (nu + 2): the
    estimate s (noiseSigma, nu = inliers - 5 residual degrees of freedom) shrunk toward the stated
    sigma s0, a prior worth 4 degrees of freedom, so that it moves from s0 to s with the number
    of inliers without a jump; and from 35 inliers on it is raised to the inliers' residual-based
    (sandwich) covariance A^-1 S A^-1 n / (n - 5) / h^2, A = J^T J, S = sum d_i^2 g_i^T g_i, along
    the directions where that exceeds it by more than its sampling noise (real matches' noise
    differs from point to point). Its calibration, and what it can be trusted for, is measured in
    doc/covariance.md. poseCovariance converts it to a 6x6 (rotation,
    translation) covariance. With #STATUS_PURE_ROTATION, 3x3: the rotation increment's alone
    (R exp([omega]x)), since t is not determined. */
    CV_PROP_RW Mat covariance;
    /** Noise estimated from the residuals of the final inliers, pixels per coordinate: the
    Sampson residuals' sum of squares over (inliers - model DoF), corrected for the truncation by
    the inlier band. With or without a camera matrix; NaN on failure, with too few inliers, or
    when the residuals fill the band as uniformly as no Gaussian would. */
    CV_PROP_RW double noiseSigma;
    /** 3x1 standard deviations of the rotation increment omega about the x, y, z axes of camera
    1's frame, degrees (square roots of the covariance's diagonal); empty without covariance. */
    CV_PROP_RW Mat rotationStdDeg;
    /** Standard deviation of the translation direction's angle along its least determined
    direction, degrees (the larger semi-axis of its 1-sigma cone); NaN without covariance. */
    CV_PROP_RW double translationStdDeg;
    /** The ambiguity test's measure (Params::ambiguityMargin): the truncated cost of the best
    distinct rival motion minus that of the returned (or rejected) one, over sigma^2; +inf when
    no distinct motion with half the support was seen or none was worth a refit (see
    Params::ambiguityMargin), NaN when the test did not run (no camera matrix, test off, or no
    motion). */
    CV_PROP_RW double rivalCostGap;
    CV_PROP_RW double timeSeconds; //!< wall time of the call
    /** Rejected, for diagnostics: when the status is not #STATUS_SUCCESS, the 3x3 F (pixels,
    ||F|| = 1) the method would have returned without the test that failed: the selected model
    when a later test (degeneracy, cheirality, acceptance after refinement) rejected it, else the
    hypothesis with the most inliers, refitted on them. Empty on success, with too few points or
    when no hypothesis was scored. Never a result: the status says it is not to be trusted. */
    CV_PROP_RW Mat rejectedF;
    //! Rejected, for diagnostics: the 3x3 rotation of rejectedF's motion (with a camera matrix)
    CV_PROP_RW Mat rejectedR;
    //! Rejected, for diagnostics: the 3x1 unit translation of rejectedF's motion (with K)
    CV_PROP_RW Mat rejectedT;
};

/** @brief A short English name of a #Status value, e.g. "poor quality input".

(A block comment on purpose: OpenCV's Python generator takes the last block comment before a
wrapped declaration as its docstring, and would otherwise reuse Report's.) */
CV_EXPORTS_W String statusToString(Status status);

/** @brief The name of a #Method as tools and samples spell it on a command line: "rcme",
"prcme", "standard", "mlesac", "covransac". An error naming `method` for another value. */
CV_EXPORTS_W String methodName(Method method);

/** @brief The #Method of a name (methodName's, in any letter case; "cov-ransac" and "cov_ransac"
too). An error naming `name` and listing the accepted names for another string. */
CV_EXPORTS_W Method methodFromString(const String& name);

//! @}

} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_PARAMS_HPP
