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

/** testScene's generic scene without noise, then on its true matches the noise of real matches
with wide tails: per coordinate of the second point, Gaussian of 0.3 px, one in four 1.2 px
(seeded by `noiseSeed`). */
inline SyntheticScene heavyTailedScene(int seed, int numPoints, uint64 noiseSeed)
{
    SyntheticScene scene = testScene(SCENE_GENERIC, seed, 0.75, 0.0, numPoints);
    RNG rng(noiseSeed);
    for (int i = 0; i < scene.points2.rows; ++i) {
        if (!scene.inlierMask.at<uchar>(i))
            continue;
        const double sigma = rng.uniform(0.0, 1.0) < 0.25 ? 1.2 : 0.3;
        scene.points2.at<double>(i, 0) += rng.gaussian(sigma);
        scene.points2.at<double>(i, 1) += rng.gaussian(sigma);
    }
    return scene;
}

/** Hand-built two views: `inliers` correspondences of points seen by K [I | 0] and K [R | t],
the rays through pixels drawn uniformly over the image, each at the depth depthOfRay(ray)
gives, with Gaussian noise of `sigma` px (points behind the second camera or outside its image
are drawn again); then uniform outliers up to `total`. points1, points2: Nx2 CV_64F. */
template <class DepthOfRay>
void projectTwoViews(RNG& rng, const Matx33d& K, const Matx33d& R, const Vec3d& t, Size image,
                     double sigma, int inliers, int total, DepthOfRay depthOfRay, Mat& points1,
                     Mat& points2)
{
    std::vector<Point2d> p1, p2;
    while (static_cast<int>(p1.size()) < inliers) {
        const Vec3d ray = K.inv() * Vec3d(rng.uniform(0.0, double(image.width)),
                                          rng.uniform(0.0, double(image.height)), 1.0);
        const Vec3d X2 = R * (ray * depthOfRay(ray)) + t;
        if (X2[2] <= 0)
            continue;
        const Vec3d x2 = K * X2;
        const Point2d q(x2[0] / x2[2] + rng.gaussian(sigma), x2[1] / x2[2] + rng.gaussian(sigma));
        if (q.x < 0 || q.x >= image.width || q.y < 0 || q.y >= image.height)
            continue;
        const Vec3d x1 = K * ray;
        p1.emplace_back(x1[0] + rng.gaussian(sigma), x1[1] + rng.gaussian(sigma));
        p2.push_back(q);
    }
    while (static_cast<int>(p1.size()) < total) {
        p1.emplace_back(rng.uniform(0.0, double(image.width)),
                        rng.uniform(0.0, double(image.height)));
        p2.emplace_back(rng.uniform(0.0, double(image.width)),
                        rng.uniform(0.0, double(image.height)));
    }
    // Rows given: OpenCV 5 makes a Mat of a vector one-dimensional, 4.x a column.
    Mat(p1).reshape(1, static_cast<int>(p1.size())).copyTo(points1);
    Mat(p2).reshape(1, static_cast<int>(p2.size())).copyTo(points2);
}

//! The well-conditioned generic scene, shared by the tests that need one.
inline SyntheticScene genericTestScene(int seed, double inlierRatio = 0.5, int numPoints = 500)
{
    return testScene(SCENE_GENERIC, seed, inlierRatio, 1.0, numPoints);
}
} // namespace opencv_test

#endif // OPENCV_RCME_TEST_PRECOMP_HPP
