// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_COMPONENT_FACTORIES_HPP
#define OPENCV_RCME_FRAMEWORK_COMPONENT_FACTORIES_HPP

// The factories of the component implementations (one file each under components/), which
// estimator_factory.cpp assembles into a method, and the option structs some of them take.

#include "framework/components.hpp"

namespace cv {
namespace rcme {
namespace detail {

// Factories of the component implementations, one file each under components/.
std::unique_ptr<Sampler> createUniformSampler(int pointCount, int sampleSize, uint64_t seed);
//! PROSAC over `order` (point indices, best first); order.size() >= sampleSize.
std::unique_ptr<Sampler> createProsacSampler(std::vector<int> order, int sampleSize, uint64_t seed);
//! With `essentialHypotheses` and calibrated data, hypotheses are projected onto the essential
//! manifold (E set); otherwise they are rank-2 F.
std::unique_ptr<MinimalSolver> createEightPointSolver(bool essentialHypotheses);
std::unique_ptr<Scorer> createInlierCountScorer(const TwoViewData& data, int sampleSize,
                                                int maxIterations);
//! MSAC's truncated cost of the Sampson distances (Params::scoring), with the count's candidate
//! test and inliers.
std::unique_ptr<Scorer> createTruncatedCostScorer(const TwoViewData& data, int sampleSize,
                                                  int maxIterations);
// cleanSampleSuccessRate: Params::cleanSampleSuccessRate (1: the classic bound).
std::unique_ptr<Termination> createAdaptiveTermination(double confidence, int maxIterations,
                                                       int sampleSize,
                                                       double cleanSampleSuccessRate = 1.0);
std::unique_ptr<Termination> createExactTermination(int iterations);
std::unique_ptr<Refiner> createGoldStandardRefiner(int maxIterations,
                                                   std::shared_ptr<const ModelSpace> space);

//! 7-point solver for F (Hartley & Zisserman 11.1.2): up to three rank-2 F per sample, exact
//! (7 parameters for 7 DoF). With calibrated data the solutions are projected to E when
//! `essentialHypotheses` is set, like the 8-point solver.
std::unique_ptr<MinimalSolver> createSevenPointSolver(bool essentialHypotheses);
//! 5-point solver for E (Nister 2004, solvers/essential_five_point.cpp; calibrated data only):
//! up to ten essential matrices per sample, exact (5 parameters for 5 DoF), returned as F with
//! their essential matrix (FundamentalForm::essential); those that cannot put the whole sample in
//! front of both cameras are dropped.
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
//! Each hypothesis of `solver` in `space` (a motion by its sample's cheirality, with K) and
//! fitted to its sample with its uncertainty.
std::unique_ptr<MinimalSolver>
createUncertainModelInstantiation(std::unique_ptr<MinimalSolver> solver,
                                  std::shared_ptr<const ModelSpace> space, int fitIterations);
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

// The stages after the loop (EstimationStage), in the order the factory runs them.
//! Box 3(b): the best candidate and its inliers, or the failure of a run without one.
std::unique_ptr<EstimationStage> createCandidateSelection();
//! Box 4: the selected model refined until its inliers settle, made the model space's estimate.
std::unique_ptr<EstimationStage> createSelectedModelRefinement();
//! Params::degeneracyTest: a homography against the final inliers (homography_comparison.cpp).
std::unique_ptr<EstimationStage> createHomographyDegeneracyTest();
//! The final fit and covariance (Params::refine).
std::unique_ptr<EstimationStage> createFinalFit();
//! Params::ambiguityMargin (> 0), calibrated data; needs EstimatorComponents::tracksRivals.
std::unique_ptr<EstimationStage> createRivalMotionDecision(double margin);
//! After the rival motion decision: the same rivals weighed at the data's measured noise.
std::unique_ptr<EstimationStage> createRivalSelectionAtDataNoise();
/** Calibrated data: the estimate's support against chance over the motions of maxIterations
samples, and with `testsTranslation` (Params::maxTranslationStdDeg > 0) its translation's. */
std::unique_ptr<EstimationStage> createChanceSupportTest(int maxIterations, bool testsTranslation);
/** Params::localOptimization with Params::refine, calibrated data: the returned motion refitted
on its inliers with a robust loss after the decisions, on success (final_polish.cpp). */
std::unique_ptr<EstimationStage> createFinalPolish(int maxIterations);
/** Params::useEstimatedNoise, calibrated data: the reported covariance raised to the final
inliers' residual-based (sandwich) one where it exceeds it (residual_covariance.cpp). */
std::unique_ptr<EstimationStage> createResidualCovariance();
//! Params::maxRotationStdDeg, maxTranslationStdDeg (each <= 0: off), calibrated data.
std::unique_ptr<EstimationStage> createUncertaintyBound(double maxRotationStdDeg,
                                                        double maxTranslationStdDeg);
//! The model space's last decision (ModelSpace::finish), after a failure too.
std::unique_ptr<EstimationStage> createFinalDecision();

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_COMPONENT_FACTORIES_HPP
