// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_TEST_PRECOMP_HPP
#define OPENCV_RCME_TEST_PRECOMP_HPP

#ifdef RCME_STANDALONE_TESTS
#include "test_standalone_shim.hpp"
#else
#include "opencv2/ts.hpp"
#endif

#include "opencv2/rcme.hpp"

// Sanitizer builds (test/hardening/): gcc defines __SANITIZE_*__, clang has __has_feature.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define RCME_SANITIZED_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) ||                         \
    __has_feature(thread_sanitizer)
#define RCME_SANITIZED_BUILD 1
#endif
#endif

namespace opencv_test {
using namespace cv::rcme;

#ifdef RCME_SANITIZED_BUILD
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif

/** How many scenes (seeds, trials) a test runs: `full` in the normal builds, `sanitized` in the
ASan + UBSan and TSan jobs. Those look for memory errors, undefined behaviour and races on the
same code paths, not for statistics, and run Eigen's code 20 to 60 times slower; the one place
that sets the size of every heavy test (doc/hardening.md). */
constexpr int testRuns(int full, int sanitized)
{
    return kSanitizedBuild ? sanitized : full;
}

/** Whether a test checks the statistics of its scenes (medians, failure counts, mean recall):
only with the full count of testRuns; each scene's own checks run in every build. */
constexpr bool kChecksStatistics = !kSanitizedBuild;

//! Scene parameters with the other fields at their defaults.
inline SceneParams testSceneParams(SceneKind kind, int seed, double inlierRatio = 0.5,
                                   double sigma = 1.0, int numPoints = 500)
{
    SceneParams sp;
    sp.kind = kind;
    sp.seed = seed;
    sp.inlierRatio = inlierRatio;
    sp.sigma = sigma;
    sp.numPoints = numPoints;
    return sp;
}

//! The scene of testSceneParams.
inline SyntheticScene testScene(SceneKind kind, int seed, double inlierRatio = 0.5,
                                double sigma = 1.0, int numPoints = 500)
{
    return generateScene(testSceneParams(kind, seed, inlierRatio, sigma, numPoints));
}

//! The well-conditioned generic scene, shared by the tests that need one.
inline SyntheticScene genericTestScene(int seed, double inlierRatio = 0.5, int numPoints = 500)
{
    return testScene(SCENE_GENERIC, seed, inlierRatio, 1.0, numPoints);
}
} // namespace opencv_test

#endif // OPENCV_RCME_TEST_PRECOMP_HPP
