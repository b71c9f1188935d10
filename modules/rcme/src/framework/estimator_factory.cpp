// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Assembles a method from components: the one place that knows which box of Fig. 1 each
// method fills with what. New methods and components are added here, not in the loop.

#include "framework/estimator_factory.hpp"

namespace cv {
namespace rcme {
namespace detail {

// A few steps suffice: the refit only has to reach its basin's bottom, and it runs often.
constexpr int kLocalOptimizationIterations = 5;

EstimatorComponents createEstimator(const Params& params, const TwoViewData& data)
{
    EstimatorComponents c;
    const bool uncertain = params.method == METHOD_RCME || params.method == METHOD_PRCME ||
                           params.method == METHOD_COV_RANSAC;
    // The methods that propagate uncertainty need a motion per hypothesis when K is known (its
    // covariance lives in the motion's tangent space); Standard scores rank-2 F and makes the
    // motion from the selected model.
    c.solver = params.solver == SOLVER_SEVEN_POINT
                   ? createSevenPointSolver(/*essentialHypotheses=*/uncertain)
                   : createEightPointSolver(/*essentialHypotheses=*/uncertain);
    if (uncertain)
        c.solver =
            createUncertainModelInstantiation(std::move(c.solver), params.sampleFitIterations);
    const int m = c.solver->sampleSize();
    if (data.size() >= m)
        c.sampler = createUniformSampler(data.size(), m,
                                         static_cast<uint64_t>(params.randomGeneratorState));
    c.termination = params.exactIterations
                        ? createExactTermination(params.maxIterations)
                        : createAdaptiveTermination(params.confidence, params.maxIterations, m);
    switch (params.method) {
    case METHOD_STANDARD:
        c.scorer = createInlierCountScorer(data, m, params.maxIterations);
        break;
    case METHOD_RCME:
    case METHOD_PRCME:
        // pRCME is RCME without the consistency test; an exact solver would not need it.
        if (params.method == METHOD_RCME && c.solver->isOverParameterized())
            c.verifiers.push_back(createModelSampleConsistencyTest(
                data.sigma, params.alpha, params.consistencyDof, params.sampleLeverage));
        c.scorer = createEntropyScorer(data, params, m);
        if (!params.exactIterations)
            c.termination =
                createEntropyTermination(std::move(c.termination), params.earlyTerminationEntropy);
        break;
    case METHOD_MLESAC:
        c.scorer = createMlesacScorer(data, params, m);
        break;
    case METHOD_COV_RANSAC:
        c.verifiers.push_back(
            createSprtVerifier(data, params, static_cast<uint64_t>(params.randomGeneratorState)));
        c.scorer = createCovarianceInlierScorer(data, params, m);
        break;
    default:
        CV_Error(Error::StsNotImplemented, "Params.method: not implemented yet");
    }
    if (params.refine && params.refineIterations > 0)
        c.refiner = createGoldStandardRefiner(params.refineIterations);
    if (params.localOptimization)
        c.localOptimizer = createGoldStandardRefiner(kLocalOptimizationIterations);
    return c;
}

} // namespace detail
} // namespace rcme
} // namespace cv
