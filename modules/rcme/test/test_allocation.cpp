// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The hypothesis loop does not allocate: the allocations of a run of 1000 iterations are those of
// a run of 200 (the buffers sized before the first hypothesis), for every method and solver.
// Counted by replacing the C allocator for the whole test binary (operator new, Eigen and
// cv::fastMalloc all end in malloc or posix_memalign), counting only inside the measured window.
// Standalone build only: it reaches cv::rcme::detail, and a sanitizer brings its own allocator.

#include "test_precomp.hpp"

#if defined(RCME_STANDALONE_TESTS) && defined(__GLIBC__) && !defined(RCME_SANITIZED_BUILD)
#define RCME_COUNT_ALLOCATIONS 1
#endif

#ifdef RCME_COUNT_ALLOCATIONS
#include "framework/candidate_set.hpp"
#include "framework/estimator_factory.hpp"
#include "framework/ransac_loop.hpp"

#include <atomic>
#include <cerrno>

extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* pointer, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void __libc_free(void* pointer);
}

namespace {
std::atomic<bool> countingAllocations{false};
std::atomic<long> allocationCount{0};

inline void countAllocation()
{
    if (countingAllocations.load(std::memory_order_relaxed))
        allocationCount.fetch_add(1, std::memory_order_relaxed);
}
} // namespace

// glibc's documented way to replace the allocator: malloc, free, calloc, realloc and the aligned
// forms, here forwarding to glibc's own.
extern "C" {
void* malloc(size_t size)
{
    countAllocation();
    return __libc_malloc(size);
}
void* calloc(size_t count, size_t size)
{
    countAllocation();
    return __libc_calloc(count, size);
}
void* realloc(void* pointer, size_t size)
{
    countAllocation();
    return __libc_realloc(pointer, size);
}
void free(void* pointer)
{
    __libc_free(pointer);
}
void* memalign(size_t alignment, size_t size)
{
    countAllocation();
    return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size)
{
    countAllocation();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size)
{
    countAllocation();
    *out = __libc_memalign(alignment, size);
    return *out ? 0 : ENOMEM;
}
}
#endif // RCME_COUNT_ALLOCATIONS

namespace opencv_test {
namespace {

#ifdef RCME_COUNT_ALLOCATIONS

using namespace cv::rcme::detail;

// Allocations made by the hypothesis loop of one run of exactly `iterations` iterations.
long loopAllocations(const SyntheticScene& s, Params params, bool calibrated, int iterations)
{
    params.exactIterations = true;
    params.maxIterations = iterations;
    const TwoViewData data =
        makeTwoViewData(s.points1, s.points2, calibrated ? s.cameraMatrix : Mat(), params);
    EstimatorComponents components = createEstimator(params, data);
    SearchResult result;
    allocationCount = 0;
    countingAllocations = true;
    searchHypotheses(data, components, result);
    countingAllocations = false;
    EXPECT_EQ(result.iterations, iterations);
    EXPECT_TRUE(result.candidates.best(*components.scorer) != nullptr); // the loop did find models
    return allocationCount;
}

TEST(Rcme_Allocation, counting_hook_sees_allocations)
{
    // The hook must see what the loop would do if it allocated (else the test below is void).
    allocationCount = 0;
    countingAllocations = true;
    std::vector<double> buffer(100);
    cv::Mat image(10, 10, CV_64F);
    Eigen::MatrixXd dynamic(5, 5);
    countingAllocations = false;
    EXPECT_GE(allocationCount.load(), 3);
    (void)buffer;
}

TEST(Rcme_Allocation, hypothesis_loop_does_not_allocate)
{
    SceneParams sp;
    sp.numPoints = 300;
    sp.seed = 3;
    const SyntheticScene s = generateScene(sp);
    struct Case
    {
        Method method;
        MinimalSolverKind solver;
        bool calibrated;
        bool localOptimization;
        bool prosac;
    };
    std::vector<Case> cases;
    for (Method method :
         {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC, METHOD_COV_RANSAC})
        for (bool calibrated : {false, true})
            cases.push_back({method, SOLVER_EIGHT_POINT, calibrated, false, false});
    cases.push_back({METHOD_RCME, SOLVER_SEVEN_POINT, true, false, false});
    cases.push_back({METHOD_STANDARD, SOLVER_SEVEN_POINT, false, false, false});
    cases.push_back({METHOD_RCME, SOLVER_FIVE_POINT, true, false, false});
    cases.push_back({METHOD_STANDARD, SOLVER_FIVE_POINT, true, false, true});
    cases.push_back({METHOD_RCME, SOLVER_EIGHT_POINT, true, true, false});
    cases.push_back({METHOD_STANDARD, SOLVER_EIGHT_POINT, false, true, false});
    for (const Case& c : cases) {
        SCOPED_TRACE(cv::format("method %d solver %d K %d LO %d PROSAC %d",
                                static_cast<int>(c.method), static_cast<int>(c.solver),
                                c.calibrated, c.localOptimization, c.prosac));
        Params params;
        params.method = c.method;
        params.solver = c.solver;
        params.localOptimization = c.localOptimization;
        params.sampler = c.prosac ? SAMPLER_PROSAC : SAMPLER_UNIFORM;
        params.randomGeneratorState = 2;
        // Once per thread, the fits' buffers take room for every point (GatheredPoints,
        // estimation/model_fit.cpp); what counts is that nothing grows with the hypotheses.
        loopAllocations(s, params, c.calibrated, 200);
        const long few = loopAllocations(s, params, c.calibrated, 200);
        const long many = loopAllocations(s, params, c.calibrated, 1000);
        EXPECT_EQ(few, many) << "allocations grow with the number of hypotheses";
    }
}

#endif // RCME_COUNT_ALLOCATIONS

} // namespace
} // namespace opencv_test
