// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Whole calls on the corridor scene (inlier ratio 0.5, sigma 1 px): every method, calibrated
// (estimateRelativeMotion with K, the camera motion) and uncalibrated (F), exactly N iterations
// or adaptive with at most N, next to OpenCV's FM_RANSAC run for exactly the same N.
// Run: build/bin/opencv_perf_rcme; check_targets.py turns one run into the ratios
// (doc/performance.md).

#include "perf_precomp.hpp"

#include "generated/enum_tables.inc"

namespace {

cv::rcme::SyntheticScene corridor(int numPoints)
{
    cv::rcme::SceneParams sp;
    sp.numPoints = numPoints;
    sp.seed = 1;
    return cv::rcme::generateScene(sp);
}

cv::rcme::Params callParams(cv::rcme::Method method, int iterations, bool exact)
{
    cv::rcme::Params params;
    params.method = method;
    params.exactIterations = exact;
    params.maxIterations = iterations;
    return params;
}

/* OpenCV 4.6's FM_RANSAC (calib3d/src/ptsetreg.cpp, 7-point kernel) starts from maxIters and only
lowers it to log(1 - confidence) / log(1 - w^7) after each better model. A confidence of exactly 1
is replaced by 0.99 (fundam.cpp accepts at most 1 - DBL_EPSILON), so the largest accepted one is
used: log(1 - confidence) = -34.7, which keeps the bound at maxIters = 1000 while the best inlier
ratio stays below 0.63 (the corridor's is 0.4 to 0.5). doc/performance.md shows the count was
checked (one cv::solveCubic per 7-point sample). */
constexpr double kOpenCvExactConfidence = 1.0 - 4 * DBL_EPSILON;

} // namespace

#ifdef RCME_GOOGLE_BENCHMARK

namespace {

struct MethodName
{
    cv::rcme::Method method;
    std::string name; //!< cv::rcme::methodName, as the samples' --method
};

// Every method of the library, from the list generated from its header.
std::vector<MethodName> allMethods()
{
    std::vector<MethodName> methods;
#define RCME_PERF_METHOD(value, name)                                                              \
    methods.push_back({cv::rcme::value, cv::rcme::methodName(cv::rcme::value)});
    RCME_METHOD_VALUES(RCME_PERF_METHOD)
#undef RCME_PERF_METHOD
    return methods;
}

// Times estimateRelativeMotion on the scene. The counters show the last report next to the time,
// so that a faster call is visibly not a failed one; "ransacIterations" is named apart from Google
// Benchmark's own "iterations" (the repetitions), which a counter would shadow.
void timeCalls(benchmark::State& state, const cv::rcme::SyntheticScene& scene, bool calibrated,
               const cv::rcme::Params& params)
{
    const cv::Mat K = calibrated ? scene.cameraMatrix : cv::Mat();
    cv::rcme::Report report;
    for (auto _ : state) {
        report = cv::rcme::estimateRelativeMotion(scene.points1, scene.points2, K, params);
        benchmark::DoNotOptimize(report.F.data);
    }
    state.counters["ransacIterations"] = report.iterations;
    state.counters["pointsPerHypothesis"] = report.pointsPerHypothesis;
    state.counters["inliers"] = report.inlierCount;
    state.counters["success"] = report.status == cv::rcme::STATUS_SUCCESS;
}

void runCall(benchmark::State& state, cv::rcme::Method method, int n, int iterations, bool exact,
             bool calibrated)
{
    timeCalls(state, corridor(n), calibrated, callParams(method, iterations, exact));
}

// RCME as the paper states it: no Gauss-Newton fit of a hypothesis to its own sample
// (Params::sampleFitIterations = 0), the like-for-like comparison with Standard's instantiation.
void runRcmeWithoutSampleFit(benchmark::State& state, int n, int iterations, bool calibrated)
{
    cv::rcme::Params params = callParams(cv::rcme::METHOD_RCME, iterations, true);
    params.sampleFitIterations = 0;
    timeCalls(state, corridor(n), calibrated, params);
}

// Params::isParallel on `threads` of OpenCV's threads; wall-clock time, the speed-up is the ratio
// of the threads:1 and threads:2 lines.
void runParallel(benchmark::State& state, cv::rcme::Method method, int n, int threads)
{
    cv::rcme::Params params = callParams(method, 1000, true);
    params.isParallel = true;
    const int previousThreads = cv::getNumThreads();
    cv::setNumThreads(threads);
    timeCalls(state, corridor(n), true, params);
    cv::setNumThreads(previousThreads);
}

void runOpenCv(benchmark::State& state, int n, int iterations)
{
    const cv::rcme::SyntheticScene scene = corridor(n);
    cv::Mat F, mask;
    for (auto _ : state) {
        F = cv::findFundamentalMat(scene.points1, scene.points2, cv::FM_RANSAC, 1.96,
                                   kOpenCvExactConfidence, iterations, mask);
        benchmark::DoNotOptimize(F.data);
    }
    state.counters["inliers"] = cv::countNonZero(mask);
}

/* Names are call/<method>/<K or F>/n:<points>/N:<iterations>/<exact|adaptive>, which
check_targets.py parses. The grid of the issue (n 100 to 10000, N 200 and 1000, exact and
adaptive) runs for Standard and RCME with K and for Standard without K (against OpenCV's
FM_RANSAC); every method runs at n 500. */
bool registerCalls()
{
    const int pointCounts[] = {100, 500, 2000, 10000};
    const int iterationCounts[] = {200, 1000};
    for (const MethodName& m : allMethods())
        for (bool calibrated : {true, false})
            for (int n : pointCounts)
                for (int N : iterationCounts)
                    for (bool exact : {true, false}) {
                        const bool grid = calibrated ? (m.method == cv::rcme::METHOD_STANDARD ||
                                                        m.method == cv::rcme::METHOD_RCME)
                                                     : m.method == cv::rcme::METHOD_STANDARD;
                        if (!grid && n != 500)
                            continue;
                        const std::string name =
                            cv::format("call/%s/%s/n:%d/N:%d/%s", m.name.c_str(),
                                       calibrated ? "K" : "F", n, N, exact ? "exact" : "adaptive");
                        benchmark::RegisterBenchmark(name.c_str(), runCall, m.method, n, N, exact,
                                                     calibrated)
                            ->Unit(benchmark::kMillisecond);
                    }
    for (bool calibrated : {true, false})
        benchmark::RegisterBenchmark(
            cv::format("call/rcme-sampleFit0/%s/n:500/N:1000/exact", calibrated ? "K" : "F")
                .c_str(),
            runRcmeWithoutSampleFit, 500, 1000, calibrated)
            ->Unit(benchmark::kMillisecond);
    for (const MethodName& m : allMethods())
        for (int threads : {1, 2})
            benchmark::RegisterBenchmark(
                cv::format("parallel/%s/K/n:2000/N:1000/exact/threads:%d", m.name.c_str(), threads)
                    .c_str(),
                runParallel, m.method, 2000, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
    for (int n : pointCounts)
        for (int N : iterationCounts)
            benchmark::RegisterBenchmark(
                cv::format("call/OpenCV_FM_RANSAC/F/n:%d/N:%d/exact", n, N).c_str(), runOpenCv, n,
                N)
                ->Unit(benchmark::kMillisecond);
    return true;
}

const bool kCallsRegistered = registerCalls();

} // namespace

#else

namespace opencv_test {
namespace {

typedef perf::TestBaseWithParam<std::tuple<int, int>> Rcme_Call;

PERF_TEST_P(Rcme_Call, estimateRelativeMotion,
            ::testing::Combine(::testing::Values(static_cast<int>(cv::rcme::METHOD_STANDARD),
                                                 static_cast<int>(cv::rcme::METHOD_RCME)),
                               ::testing::Values(100, 500, 2000)))
{
    const cv::rcme::SyntheticScene scene = corridor(std::get<1>(GetParam()));
    const cv::rcme::Params params =
        callParams(static_cast<cv::rcme::Method>(std::get<0>(GetParam())), 1000, true);
    cv::rcme::Report report;
    TEST_CYCLE()
    report =
        cv::rcme::estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
    SANITY_CHECK_NOTHING();
}

typedef perf::TestBaseWithParam<int> Rcme_OpenCvFundamentalRansac;

PERF_TEST_P(Rcme_OpenCvFundamentalRansac, findFundamentalMat, ::testing::Values(100, 500, 2000))
{
    const cv::rcme::SyntheticScene scene = corridor(GetParam());
    cv::Mat F, mask;
    TEST_CYCLE()
    F = cv::findFundamentalMat(scene.points1, scene.points2, cv::FM_RANSAC, 1.96,
                               kOpenCvExactConfidence, 1000, mask);
    SANITY_CHECK_NOTHING();
}

} // namespace
} // namespace opencv_test

#endif
