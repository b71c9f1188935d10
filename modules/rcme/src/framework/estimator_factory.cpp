// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Assembles a method from components: the one place that knows which box of Fig. 1 each
// method fills with what. New methods and components are added here, not in the loop.

#include "framework/estimator_factory.hpp"

#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"

#include <numeric>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Point indices by decreasing match quality; without scores the points are taken as sorted.
std::vector<int> qualityOrder(const Mat& quality, int pointCount)
{
    std::vector<int> order(static_cast<size_t>(pointCount));
    std::iota(order.begin(), order.end(), 0);
    if (quality.empty())
        return order;
    Mat scores;
    if (quality.total() != static_cast<size_t>(pointCount) || quality.channels() != 1 ||
        (quality.depth() != CV_32F && quality.depth() != CV_64F))
        CV_Error(Error::StsBadArg,
                 cv::format("Params.matchQuality must hold one CV_32F/CV_64F score per "
                            "correspondence (%d)",
                            pointCount));
    quality.reshape(1, pointCount).convertTo(scores, CV_64F);
    if (!checkRange(scores))
        CV_Error(Error::StsBadArg, "Params.matchQuality must be finite");
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return scores.at<double>(a) > scores.at<double>(b); });
    return order;
}

// Whether hypotheses go through SPRT before scoring (Params::verification).
bool usesSprt(const Params& params, const TwoViewData& data)
{
    switch (params.verification) {
    case VERIFICATION_SPRT:
        return true;
    case VERIFICATION_NONE:
        return false;
    default:
        return params.method == METHOD_COV_RANSAC || data.size() >= kSprtMinPoints;
    }
}

// Params::cleanSampleSuccessRate's default (0): with K a clean 5-point sample often fits a wrong
// motion (doc/results.md); without K the classic bound (1), whose third of the samples changed no
// status of the F-only suites and saved a tenth of the call on their real pairs (doc/f_only.md).
constexpr double kCalibratedCleanSampleSuccessRate = 0.3;

double cleanSampleSuccessRate(const Params& params, const TwoViewData& data)
{
    if (params.cleanSampleSuccessRate > 0)
        return params.cleanSampleSuccessRate;
    return data.calibrated ? kCalibratedCleanSampleSuccessRate : 1.0;
}

// Params::scoring of METHOD_STANDARD. With K the count is kept: its bail-out stops a hypothesis
// sooner, and the rival memory and the decisions after the loop were tuned on it.
bool ranksByTruncatedCost(const Params& params, const TwoViewData& data)
{
    switch (params.scoring) {
    case SCORING_TRUNCATED_COST:
        return true;
    case SCORING_INLIER_COUNT:
        return false;
    default:
        return !data.calibrated;
    }
}

} // namespace

std::unique_ptr<ModelSpace> createModelSpace(const TwoViewData& data)
{
    return data.calibrated ? createMotionSpace() : createFundamentalSpace();
}

// A few steps suffice: the refit only has to reach its basin's bottom, and it runs often.
constexpr int kLocalOptimizationIterations = 5;
// Inner minimal samples per round of inner sampling (doc/experiments_archive.md, "Inner sampling":
// on the tuning corridors at w = 0.3, 20, 50, 100 and 200 left 17, 12, 5 and 2 of 200 wrong motions
// with success, 31 without; 200 raised the false alarms from 5 to 11).
constexpr int kInnerSamplesPerRound = 100;
// The share of clean minimal samples that fit the right motion, as inner sampling assumes it: it
// runs when Params::maxIterations samples fall short of log(1 - p) / log(1 - q w^m) for the best
// candidate's inlier ratio w, in adaptive loops too. Lower than the adaptive bound's
// cleanSampleSuccessRate (0.3 with K), because a wrong motion costs far more than 100 inner
// samples: with 1000 5-point samples it turns inner sampling on below inlier ratios of about
// 0.55, where the corridor's loops select wrong motions, and not on the real pairs' (median time
// unchanged). On the tuning scenes (doc/experiments_archive.md, "Inner sampling"), exactly
// N = 1000, q = 0.3, 0.2, 0.15, 0.1 left 15, 12, 9, 9 wrong motions with success of 820 runs;
// 0.1 flagged fewer right ones than 0.15.
constexpr double kInnerSamplingSuccessRate = 0.1;

EstimatorComponents createEstimator(const Params& params, const TwoViewData& data)
{
    EstimatorComponents c;
    c.space = createModelSpace(data);
    const bool uncertain = params.method == METHOD_RCME || params.method == METHOD_PRCME ||
                           params.method == METHOD_COV_RANSAC;
    // The methods that propagate uncertainty need a motion per hypothesis when K is known (its
    // covariance lives in the motion's tangent space); Standard scores rank-2 F and makes the
    // motion from the selected model.
    // Without K the 7-point solver, as OpenCV's and USAC's F estimators: one point fewer per
    // sample finds a clean sample in 1000 at lower inlier ratios, and it fits its sample exactly
    // (doc/f_only.md, "The 7-point sample without K").
    MinimalSolverKind solver = params.solver;
    if (solver == SOLVER_AUTO)
        solver = data.calibrated ? SOLVER_FIVE_POINT : SOLVER_SEVEN_POINT;
    switch (solver) {
    case SOLVER_FIVE_POINT:
        if (!data.calibrated)
            CV_Error(Error::StsBadArg,
                     "Params.solver: SOLVER_FIVE_POINT needs a camera matrix (it estimates E)");
        c.solver = createFivePointSolver();
        break;
    case SOLVER_SEVEN_POINT:
        c.solver = createSevenPointSolver(/*essentialHypotheses=*/uncertain);
        break;
    default:
        c.solver = createEightPointSolver(/*essentialHypotheses=*/uncertain);
    }
    if (uncertain)
        c.solver = createUncertainModelInstantiation(std::move(c.solver), c.space,
                                                     params.sampleFitIterations);
    const int m = c.solver->sampleSize();
    if (data.size() >= m) {
        const uint64_t seed = static_cast<uint64_t>(params.randomGeneratorState);
        c.sampler =
            params.sampler == SAMPLER_PROSAC
                ? createProsacSampler(qualityOrder(params.matchQuality, data.size()), m, seed)
                : createUniformSampler(data.size(), m, seed);
    }
    c.termination = params.exactIterations
                        ? createExactTermination(params.maxIterations)
                        : createAdaptiveTermination(params.confidence, params.maxIterations, m,
                                                    cleanSampleSuccessRate(params, data));
    switch (params.method) {
    case METHOD_STANDARD:
        c.scorer = ranksByTruncatedCost(params, data)
                       ? createTruncatedCostScorer(data, m, params.maxIterations)
                       : createInlierCountScorer(data, m, params.maxIterations);
        break;
    case METHOD_RCME:
    case METHOD_PRCME:
        // pRCME is RCME without the consistency test; an exact solver would not need it.
        if (params.method == METHOD_RCME && c.solver->isOverParameterized())
            c.verifiers.push_back(createModelSampleConsistencyTest(data, params.sampleLeverage));
        c.scorer = createEntropyScorer(data, entropyOptions(params), m, params.maxIterations);
        if (!params.exactIterations)
            c.termination =
                createEntropyTermination(std::move(c.termination), params.earlyTerminationEntropy);
        break;
    case METHOD_MLESAC:
        c.scorer = createMlesacScorer(data, m, params.maxIterations);
        break;
    case METHOD_COV_RANSAC:
        c.scorer = createCovarianceInlierScorer(data, m, params.maxIterations);
        break;
    default:
        CV_Error(Error::StsNotImplemented, "Params.method: not implemented yet");
    }
    if (usesSprt(params, data)) {
        // The method's own inlier test is SPRT's consistency: propagated uncertainty where the
        // hypotheses carry it, the threshold's band otherwise.
        const uint64_t seed = static_cast<uint64_t>(params.randomGeneratorState);
        c.verifiers.push_back(uncertain ? createSprtVerifier(data, seed)
                                        : createBandSprtVerifier(data, seed));
    }
    if (params.refine && params.refineIterations > 0)
        c.refiner = createGoldStandardRefiner(params.refineIterations, c.space);
    if (params.localOptimization) {
        c.localOptimizer = createGoldStandardRefiner(kLocalOptimizationIterations, c.space);
        c.innerSampling.samplesPerRound = kInnerSamplesPerRound;
        c.innerSampling.confidence = params.confidence;
        c.innerSampling.successRate =
            std::min(cleanSampleSuccessRate(params, data), kInnerSamplingSuccessRate);
        c.innerSampling.maxIterations = params.maxIterations;
        c.innerSampling.seed = static_cast<uint64_t>(params.randomGeneratorState);
    }
    c.parallel = params.isParallel;
    // The stages after the loop, in the order of Fig. 1: select, refine, decide, finalize.
    c.stages.push_back(createCandidateSelection());
    c.stages.push_back(createSelectedModelRefinement());
    if (params.degeneracyTest)
        c.stages.push_back(createHomographyDegeneracyTest());
    c.stages.push_back(createFinalFit());
    // The decisions after the final fit weigh motions: F alone has no rotation or translation to
    // bound.
    if (data.calibrated && params.ambiguityMargin > 0) {
        c.stages.push_back(createRivalMotionDecision(params.ambiguityMargin));
        c.stages.push_back(createRivalSelectionAtDataNoise());
        c.tracksRivals = true;
    }
    if (data.calibrated)
        c.stages.push_back(
            createChanceSupportTest(params.maxIterations, params.maxTranslationStdDeg > 0));
    if (data.calibrated && (params.maxRotationStdDeg > 0 || params.maxTranslationStdDeg > 0))
        c.stages.push_back(
            createUncertaintyBound(params.maxRotationStdDeg, params.maxTranslationStdDeg));
    if (data.calibrated && params.localOptimization && c.refiner)
        c.stages.push_back(createFinalPolish(params.refineIterations));
    if (data.calibrated && params.useEstimatedNoise)
        c.stages.push_back(createResidualCovariance());
    c.stages.push_back(createFinalDecision());
    return c;
}

} // namespace detail
} // namespace rcme
} // namespace cv
