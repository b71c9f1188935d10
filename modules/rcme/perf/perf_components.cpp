// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The boxes one at a time (standalone build only: they live in cv::rcme::detail): each minimal
// solver per sample, RCME's instantiation with its fit and covariance per sample, and each
// scorer per point (the time per point is 1 / items_per_second). Corridor scene, n = 2000.

#include "perf_precomp.hpp"

#ifdef RCME_GOOGLE_BENCHMARK

#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "framework/random.hpp"
#include "framework/two_view_data.hpp"

namespace {

using namespace cv::rcme::detail;

struct Problem
{
    TwoViewData data;
    std::vector<std::vector<int>> samples; //!< minimal samples of inliers
};

Problem makeProblem(int sampleSize, bool calibrated)
{
    cv::rcme::SceneParams sp;
    sp.numPoints = 2000;
    sp.seed = 1;
    const cv::rcme::SyntheticScene scene = cv::rcme::generateScene(sp);
    cv::rcme::Params params;
    Problem problem;
    problem.data = makeTwoViewData(scene.points1, scene.points2,
                                   calibrated ? scene.cameraMatrix : cv::Mat(), params);
    std::vector<int> inliers;
    for (int i = 0; i < scene.inlierMask.rows; ++i)
        if (scene.inlierMask.at<uchar>(i))
            inliers.push_back(i);
    // A fixed set of samples, cycled through by the benchmark loops.
    uint64_t state = 7;
    for (int s = 0; s < 64; ++s) {
        std::vector<int> sample(static_cast<size_t>(sampleSize));
        drawDistinct(state, static_cast<uint32_t>(inliers.size()), 0, sample);
        for (int& index : sample)
            index = inliers[static_cast<size_t>(index)];
        problem.samples.push_back(sample);
    }
    return problem;
}

void runSolver(benchmark::State& state, std::unique_ptr<MinimalSolver> (*create)(), bool calibrated)
{
    std::unique_ptr<MinimalSolver> solver = create();
    const Problem problem = makeProblem(solver->sampleSize(), calibrated);
    std::vector<Model> models;
    models.reserve(static_cast<size_t>(solver->maxSolutions()));
    size_t next = 0, solutions = 0;
    for (auto _ : state) {
        solutions +=
            static_cast<size_t>(solver->estimate(problem.data, problem.samples[next], models));
        next = (next + 1) % problem.samples.size();
    }
    state.counters["solutions"] =
        static_cast<double>(solutions) / static_cast<double>(state.iterations());
}

std::unique_ptr<MinimalSolver> eightPoint()
{
    return createEightPointSolver(false);
}
std::unique_ptr<MinimalSolver> sevenPoint()
{
    return createSevenPointSolver(false);
}
std::unique_ptr<MinimalSolver> fivePoint()
{
    return createFivePointSolver();
}
std::unique_ptr<MinimalSolver> rcmeEightPoint()
{
    return createUncertainModelInstantiation(createEightPointSolver(true), createMotionSpace(), 5);
}

// The fit's own cost is the difference of the two RCME lines (its covariance needs no fit).
std::unique_ptr<MinimalSolver> rcmeEightPointWithoutFit()
{
    return createUncertainModelInstantiation(createEightPointSolver(true), createMotionSpace(), 0);
}

BENCHMARK_CAPTURE(runSolver, 8point, eightPoint, false)->Name("solver/8-point");
BENCHMARK_CAPTURE(runSolver, 7point, sevenPoint, false)->Name("solver/7-point");
BENCHMARK_CAPTURE(runSolver, 5point, fivePoint, true)->Name("solver/5-point");
BENCHMARK_CAPTURE(runSolver, rcme, rcmeEightPoint, true)
    ->Name("solver/RCME-instantiation(8-point,fit5,covariance)");
BENCHMARK_CAPTURE(runSolver, rcmeNoFit, rcmeEightPointWithoutFit, true)
    ->Name("solver/RCME-instantiation(8-point,fit0,covariance)");

enum ScorerKind
{
    COUNT,
    MLESAC,
    COV_RANSAC,
    RCME
};

void runScorer(benchmark::State& state, ScorerKind kind)
{
    const Problem problem = makeProblem(8, true);
    cv::rcme::Params params;
    // One hypothesis with its motion and covariance, as RCME's instantiation makes them.
    std::vector<Model> models;
    rcmeEightPoint()->estimate(problem.data, problem.samples[0], models);
    if (models.empty()) {
        state.SkipWithError("the sample gave no hypothesis");
        return;
    }
    std::unique_ptr<Scorer> scorer;
    switch (kind) {
    case COUNT:
        scorer = createInlierCountScorer(problem.data, 8, 1000);
        break;
    case MLESAC:
        scorer = createMlesacScorer(problem.data, 8, params.maxIterations);
        break;
    case COV_RANSAC:
        scorer = createCovarianceInlierScorer(problem.data, 8, params.maxIterations);
        break;
    case RCME:
        scorer = createEntropyScorer(problem.data, entropyOptions(params), 8, params.maxIterations);
        break;
    }
    Score score;
    for (auto _ : state) {
        score = scorer->evaluate(problem.data, models[0]);
        benchmark::DoNotOptimize(score.value);
    }
    state.SetItemsProcessed(state.iterations() * problem.data.size());
    state.counters["inliers"] = score.inlierCount;
}

BENCHMARK_CAPTURE(runScorer, count, COUNT)->Name("score-per-point/count");
BENCHMARK_CAPTURE(runScorer, mlesac, MLESAC)->Name("score-per-point/MLESAC");
BENCHMARK_CAPTURE(runScorer, cov, COV_RANSAC)->Name("score-per-point/Cov-RANSAC");
BENCHMARK_CAPTURE(runScorer, rcme, RCME)->Name("score-per-point/RCME");

} // namespace

#endif // RCME_GOOGLE_BENCHMARK
