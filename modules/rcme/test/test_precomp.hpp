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

//! The well-conditioned generic scene of generateScene, shared by the tests that need one.
inline SyntheticScene genericTestScene(int seed, double inlierRatio = 0.5, int numPoints = 500)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.seed = seed;
    sp.inlierRatio = inlierRatio;
    sp.numPoints = numPoints;
    return generateScene(sp);
}
} // namespace opencv_test

#endif // OPENCV_RCME_TEST_PRECOMP_HPP
