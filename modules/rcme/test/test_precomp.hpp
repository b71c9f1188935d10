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

namespace opencv_test {
using namespace cv::rcme;

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
