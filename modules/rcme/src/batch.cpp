// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Many independent estimations on a pool of threads. Pairs are handed out one at a time from an
// atomic counter, because their costs differ (point counts, adaptive iteration counts).

#include "precomp.hpp"

#include <atomic>
#include <exception>
#include <system_error>
#include <thread>

namespace cv {
namespace rcme {

std::vector<Report> estimateRelativeMotionBatch(const std::vector<Mat>& points1,
                                                const std::vector<Mat>& points2,
                                                const std::vector<Mat>& cameraMatrices,
                                                const Params& params, int threads)
{
    const size_t numPairs = points1.size();
    if (points2.size() != numPairs)
        CV_Error(Error::StsUnmatchedSizes,
                 format("estimateRelativeMotionBatch: points2 has %zu entries, points1 %zu",
                        points2.size(), numPairs));
    if (cameraMatrices.size() > 1 && cameraMatrices.size() != numPairs)
        CV_Error(Error::StsUnmatchedSizes,
                 format("estimateRelativeMotionBatch: cameraMatrices has %zu entries; expected "
                        "0, 1 or one per pair (%zu)",
                        cameraMatrices.size(), numPairs));
    auto cameraOf = [&](size_t i) -> Mat {
        if (cameraMatrices.empty())
            return Mat();
        return cameraMatrices.size() == 1 ? cameraMatrices[0] : cameraMatrices[i];
    };

    std::vector<Report> reports(numPairs);
    std::vector<std::exception_ptr> errors(numPairs);
    std::atomic<size_t> next(0);
    auto work = [&] {
        for (size_t i = next.fetch_add(1); i < numPairs; i = next.fetch_add(1)) {
            try {
                reports[i] = estimateRelativeMotion(points1[i], points2[i], cameraOf(i), params);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
    };
    const size_t wanted = threads > 0 ? static_cast<size_t>(threads)
                                      : static_cast<size_t>(std::max(getNumberOfCPUs(), 1));
    const size_t numThreads = std::min(wanted, numPairs);
    if (numThreads <= 1) {
        work();
    } else {
        std::vector<std::thread> pool;
        pool.reserve(numThreads - 1);
        try {
            for (size_t t = 1; t < numThreads; ++t)
                pool.emplace_back(work);
        } catch (const std::system_error&) {
            // fewer threads than asked for: the ones started share the pairs
        }
        work(); // the calling thread is one of the workers
        for (auto& thread : pool)
            thread.join();
    }

    for (size_t i = 0; i < numPairs; ++i) {
        if (!errors[i])
            continue;
        try {
            std::rethrow_exception(errors[i]);
        } catch (const Exception& e) {
            Exception prefixed = e;
            prefixed.err = format("pair %zu: ", i) + e.err;
            prefixed.formatMessage();
            throw prefixed;
        }
    }
    return reports;
}

} // namespace rcme
} // namespace cv
