// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Params::isParallel: hypotheses spread over OpenCV's threads give, for a given seed, the result
// of a sequential run, whatever the thread count and for every method, solver and option.

#include "test_precomp.hpp"

namespace opencv_test {
namespace {

// Restores OpenCV's thread count when a test ends, even on failure.
struct ThreadCountGuard
{
    int previous = cv::getNumThreads();
    ~ThreadCountGuard() { cv::setNumThreads(previous); }
};

/** `actual` (a parallel run) has the result of `expected`. With `sameWork`, also the same points
per hypothesis; otherwise at least as many: a sequential run knows the best count before each
hypothesis, a parallel one only before each batch, so METHOD_STANDARD's count stops no earlier. */
void expectSameReport(const Report& expected, const Report& actual, const std::string& what,
                      bool sameWork = true)
{
    SCOPED_TRACE(what);
    ASSERT_EQ(expected.status, actual.status);
    EXPECT_EQ(expected.iterations, actual.iterations);
    EXPECT_EQ(expected.inlierCount, actual.inlierCount);
    EXPECT_EQ(cv::norm(expected.mask, actual.mask, NORM_INF), 0);
    // Counted on the committed hypotheses only, so SPRT's saving reads the same too.
    if (cvIsNaN(expected.pointsPerHypothesis))
        EXPECT_TRUE(cvIsNaN(actual.pointsPerHypothesis));
    else if (sameWork)
        EXPECT_EQ(expected.pointsPerHypothesis, actual.pointsPerHypothesis);
    else
        EXPECT_LE(expected.pointsPerHypothesis, actual.pointsPerHypothesis);
    if (expected.status != STATUS_SUCCESS)
        return;
    // Bit for bit: the same hypotheses are committed in the same order.
    EXPECT_EQ(cv::norm(expected.F, actual.F, NORM_INF), 0);
    if (!expected.R.empty()) {
        EXPECT_EQ(cv::norm(expected.R, actual.R, NORM_INF), 0);
        EXPECT_EQ(cv::norm(expected.t, actual.t, NORM_INF), 0);
    }
    if (cvIsNaN(expected.meanEntropy))
        EXPECT_TRUE(cvIsNaN(actual.meanEntropy));
    else
        EXPECT_EQ(expected.meanEntropy, actual.meanEntropy);
}

struct Variant
{
    Method method;
    MinimalSolverKind solver;
    bool calibrated;
    bool localOptimization;
    bool exactIterations;
};

TEST(Rcme_Parallel, same_result_for_every_thread_count)
{
    ThreadCountGuard guard;
    SceneParams sp;
    sp.numPoints = 300;
    sp.seed = 4;
    const SyntheticScene s = generateScene(sp);
    std::vector<Variant> variants;
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
        for (bool calibrated : {false, true})
            variants.push_back({method, SOLVER_EIGHT_POINT, calibrated, false, false});
    // Exact N (a bound that never moves), local optimisation and the other solvers.
    variants.push_back({METHOD_RCME, SOLVER_EIGHT_POINT, true, false, true});
    variants.push_back({METHOD_STANDARD, SOLVER_EIGHT_POINT, true, true, false});
    variants.push_back({METHOD_RCME, SOLVER_EIGHT_POINT, true, true, false});
    variants.push_back({METHOD_RCME, SOLVER_SEVEN_POINT, true, false, false});
    variants.push_back({METHOD_COV_RANSAC, SOLVER_FIVE_POINT, true, false, false});
    variants.push_back({METHOD_MLESAC, SOLVER_SEVEN_POINT, false, false, false});
    // The defaults: 300 samples fall short of the 5-point bound, so inner samples are drawn.
    variants.push_back({METHOD_STANDARD, SOLVER_FIVE_POINT, true, true, false});
    for (const Variant& v : variants) {
        Params params;
        params.method = v.method;
        params.solver = v.solver;
        params.localOptimization = v.localOptimization;
        params.exactIterations = v.exactIterations;
        params.maxIterations = 300;
        params.randomGeneratorState = 9;
        const Mat K = v.calibrated ? s.cameraMatrix : Mat();
        const Report sequential = estimateRelativeMotion(s.points1, s.points2, K, params);
        params.isParallel = true;
        Report firstParallel;
        for (int threads : {1, 2, 3}) {
            cv::setNumThreads(threads);
            const Report parallel = estimateRelativeMotion(s.points1, s.points2, K, params);
            const std::string what =
                cv::format("method %d solver %d K %d LO %d exact %d threads %d",
                           static_cast<int>(v.method), static_cast<int>(v.solver), v.calibrated,
                           v.localOptimization, v.exactIterations, threads);
            expectSameReport(sequential, parallel, what, v.method != METHOD_STANDARD);
            if (threads == 1)
                firstParallel = parallel;
            else
                expectSameReport(firstParallel, parallel, what);
        }
    }
}

TEST(Rcme_Parallel, failures_are_the_same)
{
    ThreadCountGuard guard;
    SceneParams sp;
    sp.numPoints = 200;
    sp.inlierRatio = 0.0; // poor quality input
    sp.seed = 5;
    const SyntheticScene s = generateScene(sp);
    for (Method method : {METHOD_STANDARD, METHOD_RCME, METHOD_COV_RANSAC}) {
        Params params;
        params.method = method;
        params.maxIterations = 150;
        const Report sequential =
            estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_NE(sequential.status, STATUS_SUCCESS);
        params.isParallel = true;
        cv::setNumThreads(2);
        expectSameReport(
            sequential, estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params),
            cv::format("method %d", static_cast<int>(method)), method != METHOD_STANDARD);
    }
}

} // namespace
} // namespace opencv_test
