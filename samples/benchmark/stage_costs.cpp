// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// What each stage of the default costs and what it catches, on real pairs (speed.py's "Cost per
// stage" section). The library is untouched: each stage of the method is wrapped in a timer that
// also records the verdicts it returns, so the figures cost the library nothing when they are not
// asked for.
//
//     rcme_stage_costs PAIRS ITERATIONS CONFIDENCE SIGMA THRESHOLD REPEATS [adaptive|exact]
//
// PAIRS is a binary file (speed.py writes it): int32 pair count, then per pair int32 n, the 3x3
// camera matrix (9 float64, row-major; all zeros: no camera matrix, the F-only call) and n
// points of image 1 then n of image 2 (2 float64 each). Each pair runs REPEATS times in adaptive
// mode and REPEATS times with exactly ITERATIONS samples (one mode only when named, e.g. to profile
// it); a stage's time on a pair is the fastest of its runs. Prints one JSON object per mode: per
// pair the setup, the loop and each stage that ran (seconds), and the verdicts and model revisions
// each stage returned.

#include "framework/estimation_pipeline.hpp"
#include "framework/estimator_factory.hpp"
#include "framework/two_view_data.hpp"

#include <cxxabi.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

namespace {

using namespace cv::rcme;
using namespace cv::rcme::detail;

struct Pair
{
    cv::Mat K, points1, points2;
};

std::vector<Pair> readPairs(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error("cannot read " + path);
    int32_t count = 0;
    in.read(reinterpret_cast<char*>(&count), sizeof count);
    std::vector<Pair> pairs(static_cast<size_t>(count));
    for (Pair& pair : pairs) {
        int32_t n = 0;
        in.read(reinterpret_cast<char*>(&n), sizeof n);
        pair.K.create(3, 3, CV_64F);
        pair.points1.create(n, 2, CV_64F);
        pair.points2.create(n, 2, CV_64F);
        in.read(reinterpret_cast<char*>(pair.K.ptr<double>()), 9 * sizeof(double));
        in.read(reinterpret_cast<char*>(pair.points1.ptr<double>()), 2 * n * sizeof(double));
        in.read(reinterpret_cast<char*>(pair.points2.ptr<double>()), 2 * n * sizeof(double));
        if (cv::countNonZero(pair.K) == 0)
            pair.K.release();
    }
    if (!in)
        throw std::runtime_error(path + " is truncated");
    return pairs;
}

// The class name of a stage, without its namespaces.
std::string stageName(const EstimationStage& stage)
{
    int status = 0;
    char* demangled = abi::__cxa_demangle(typeid(stage).name(), nullptr, nullptr, &status);
    std::string name = status == 0 ? demangled : typeid(stage).name();
    std::free(demangled);
    const size_t colon = name.rfind("::");
    return colon == std::string::npos ? name : name.substr(colon + 2);
}

double seconds(int64 ticks)
{
    return static_cast<double>(ticks) / cv::getTickFrequency();
}

// One run of one stage: its time and what it returned.
struct StageRun
{
    std::string name;
    bool ran = false;
    double seconds = 0.0;
    bool revised = false; //!< it replaced the model
    int verdict = -1;     //!< the status it set, -1 for none
};

// A stage with a timer around it, writing to its entry of the run.
class TimedStage final : public EstimationStage
{
public:
    TimedStage(std::unique_ptr<EstimationStage> inner, StageRun& record)
        : inner_(std::move(inner)), record_(record)
    {
        record_.name = stageName(*inner_);
    }
    bool runsOnFailure() const override { return inner_->runsOnFailure(); }
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const int64 start = cv::getTickCount();
        StageOutcome outcome = inner_->run(context, estimate);
        record_.seconds = seconds(cv::getTickCount() - start);
        record_.ran = true;
        record_.revised = outcome.model.has_value();
        record_.verdict = outcome.verdict ? static_cast<int>(outcome.verdict->status) : -1;
        return outcome;
    }

private:
    std::unique_ptr<EstimationStage> inner_;
    StageRun& record_;
};

struct Run
{
    double setup = 0.0, loop = 0.0, total = 0.0;
    int status = STATUS_SUCCESS;
    std::vector<StageRun> stages; //!< in the pipeline's order
};

Run runOnce(const Pair& pair, const Params& params)
{
    Run run;
    const int64 start = cv::getTickCount();
    const TwoViewData data = makeTwoViewData(pair.points1, pair.points2, pair.K, params);
    EstimatorComponents components = createEstimator(params, data);
    run.stages.resize(components.stages.size());
    for (size_t k = 0; k < components.stages.size(); ++k)
        components.stages[k] =
            std::make_unique<TimedStage>(std::move(components.stages[k]), run.stages[k]);
    const int64 loopStart = cv::getTickCount();
    run.setup = seconds(loopStart - start);
    const Estimation estimation = estimateModel(data, components);
    run.total = seconds(cv::getTickCount() - start);
    double stages = 0.0;
    for (const StageRun& stage : run.stages)
        stages += stage.seconds;
    run.loop = run.total - run.setup - stages;
    run.status = estimation.estimate.status;
    return run;
}

// The fastest of `repeats` runs, field by field (the runs are identical but for their timing).
Run fastest(const Pair& pair, const Params& params, int repeats)
{
    Run best = runOnce(pair, params);
    for (int r = 1; r < repeats; ++r) {
        const Run next = runOnce(pair, params);
        best.setup = std::min(best.setup, next.setup);
        best.loop = std::min(best.loop, next.loop);
        best.total = std::min(best.total, next.total);
        for (size_t k = 0; k < best.stages.size(); ++k)
            best.stages[k].seconds = std::min(best.stages[k].seconds, next.stages[k].seconds);
    }
    return best;
}

void printRun(const Run& run)
{
    std::printf("{\"setup\": %.9g, \"loop\": %.9g, \"total\": %.9g, \"status\": %d, \"stages\": [",
                run.setup, run.loop, run.total, run.status);
    for (size_t k = 0; k < run.stages.size(); ++k) {
        const StageRun& stage = run.stages[k];
        std::printf("%s{\"name\": \"%s\", \"ran\": %s, \"seconds\": %.9g, \"revised\": %s, "
                    "\"verdict\": %d}",
                    k ? ", " : "", stage.name.c_str(), stage.ran ? "true" : "false", stage.seconds,
                    stage.revised ? "true" : "false", stage.verdict);
    }
    std::printf("]}");
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 7 && argc != 8) {
        std::cerr << "usage: rcme_stage_costs PAIRS ITERATIONS CONFIDENCE SIGMA THRESHOLD "
                     "REPEATS [adaptive|exact]\n";
        return 2;
    }
    try {
        const std::vector<Pair> pairs = readPairs(argv[1]);
        Params params;
        params.maxIterations = std::stoi(argv[2]);
        const double confidence = std::stod(argv[3]);
        params.sigma = std::stod(argv[4]);
        params.threshold = std::stod(argv[5]);
        params.randomGeneratorState = 0;
        const int repeats = std::max(1, std::stoi(argv[6]));
        cv::setNumThreads(1);
        std::printf("{");
        const std::string only = argc == 8 ? argv[7] : "";
        const char* separator = "";
        for (int exact = 0; exact < 2; ++exact) {
            if (!only.empty() && only != (exact ? "exact" : "adaptive"))
                continue;
            params.exactIterations = exact == 1;
            // As speed.py: the adaptive runs at the given confidence, the exact ones at the
            // default's (which LO-RANSAC's inner sampling reads).
            params.confidence = exact ? Params().confidence : confidence;
            std::printf("%s\"%s\": [", separator, exact ? "exact" : "adaptive");
            separator = ", ";
            for (size_t p = 0; p < pairs.size(); ++p) {
                std::printf("%s", p ? ", " : "");
                printRun(fastest(pairs[p], params, repeats));
            }
            std::printf("]");
        }
        std::printf("}\n");
    } catch (const std::exception& e) {
        std::cerr << "rcme_stage_costs: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
