// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Whole calls on the corridor scene, rcme's Standard next to OpenCV's FM_RANSAC at the same
// exact iteration count. Run: build/bin/opencv_perf_rcme (see README, "Performance").

#include "perf_precomp.hpp"

namespace {

cv::rcme::SyntheticScene corridor(int numPoints)
{
    cv::rcme::SceneParams sp;
    sp.numPoints = numPoints;
    sp.seed = 1;
    return cv::rcme::generateScene(sp);
}

cv::rcme::Params exactStandard(int iterations)
{
    cv::rcme::Params params;
    params.method = cv::rcme::METHOD_STANDARD;
    params.exactIterations = true;
    params.maxIterations = iterations;
    return params;
}

} // namespace

#ifdef RCME_GOOGLE_BENCHMARK

static void BM_StandardFundamental(benchmark::State& state)
{
    const cv::rcme::SyntheticScene scene = corridor(static_cast<int>(state.range(0)));
    const cv::rcme::Params params = exactStandard(static_cast<int>(state.range(1)));
    cv::Mat mask;
    cv::rcme::Status status;
    for (auto _ : state)
        benchmark::DoNotOptimize(
            cv::rcme::findFundamentalMat(scene.points1, scene.points2, params, mask, status));
}
BENCHMARK(BM_StandardFundamental)
    ->ArgsProduct({{100, 500, 2000}, {200, 1000}})
    ->Unit(benchmark::kMillisecond);

static void BM_OpenCVFundamentalRansac(benchmark::State& state)
{
    const cv::rcme::SyntheticScene scene = corridor(static_cast<int>(state.range(0)));
    cv::Mat mask;
    // A confidence of ~1 keeps OpenCV's adaptive bound at maxIters, the same exact count.
    for (auto _ : state)
        benchmark::DoNotOptimize(cv::findFundamentalMat(scene.points1, scene.points2, cv::FM_RANSAC,
                                                        1.96, 1.0 - 1e-12,
                                                        static_cast<int>(state.range(1)), mask));
}
BENCHMARK(BM_OpenCVFundamentalRansac)
    ->ArgsProduct({{100, 500, 2000}, {200, 1000}})
    ->Unit(benchmark::kMillisecond);

#else

namespace opencv_test {
namespace {

typedef perf::TestBaseWithParam<int> Rcme_Standard;

PERF_TEST_P(Rcme_Standard, findFundamentalMat, ::testing::Values(100, 500, 2000))
{
    const cv::rcme::SyntheticScene scene = corridor(GetParam());
    const cv::rcme::Params params = exactStandard(1000);
    cv::Mat F, mask;
    cv::rcme::Status status;
    TEST_CYCLE()
    F = cv::rcme::findFundamentalMat(scene.points1, scene.points2, params, mask, status);
    SANITY_CHECK_NOTHING();
}

} // namespace
} // namespace opencv_test

#endif
