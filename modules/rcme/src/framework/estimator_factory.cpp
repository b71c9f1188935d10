// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Assembles a method from components: the one place that knows which box of Fig. 1 each
// method fills with what. New methods and components are added here, not in the loop.

#include "framework/estimator_factory.hpp"

namespace cv {
namespace rcme {
namespace detail {

EstimatorComponents createEstimator(const Params& params, const TwoViewData& data)
{
    EstimatorComponents c;
    c.solver = createEightPointSolver(/*essentialHypotheses=*/false);
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
    default:
        CV_Error(Error::StsNotImplemented, "Params.method: not implemented yet");
    }
    if (params.refine && params.refineIterations > 0)
        c.refiner = createGoldStandardRefiner(params.refineIterations);
    return c;
}

} // namespace detail
} // namespace rcme
} // namespace cv
