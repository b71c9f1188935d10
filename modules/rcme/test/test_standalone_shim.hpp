// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// What the tests use of OpenCV's ts module, for the standalone build: Debian installs no
// opencv_ts, so the same test files run on plain GoogleTest.
#ifndef OPENCV_RCME_TEST_STANDALONE_SHIM_HPP
#define OPENCV_RCME_TEST_STANDALONE_SHIM_HPP

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cstdlib>
#include <string>

namespace opencv_test {
using namespace cv;
using namespace testing;
using std::string;
using std::vector;

// ts hides these cv:: names inside opencv_test so that tests spell them cv::norm etc. (they
// collide with test helpers elsewhere); hiding them here too makes the standalone build reject
// what the in-tree build would.
#define RCME_TEST_GUARD_SYMBOL(name)                                                               \
    class required_namespace_specification_here_for_symbol_##name                                  \
    {                                                                                              \
    };                                                                                             \
    using name = required_namespace_specification_here_for_symbol_##name;
RCME_TEST_GUARD_SYMBOL(norm)
RCME_TEST_GUARD_SYMBOL(add)
RCME_TEST_GUARD_SYMBOL(multiply)
RCME_TEST_GUARD_SYMBOL(divide)
RCME_TEST_GUARD_SYMBOL(transpose)
RCME_TEST_GUARD_SYMBOL(copyMakeBorder)
RCME_TEST_GUARD_SYMBOL(filter2D)
RCME_TEST_GUARD_SYMBOL(compare)
RCME_TEST_GUARD_SYMBOL(minMaxIdx)
RCME_TEST_GUARD_SYMBOL(threshold)
#undef RCME_TEST_GUARD_SYMBOL
} // namespace opencv_test

// Same role as ts's CV_TEST_MAIN: reseed cv::theRNG() before each test so failures reproduce.
class RcmeReseedListener : public ::testing::EmptyTestEventListener
{
    void OnTestStart(const ::testing::TestInfo&) override { cv::theRNG() = cv::RNG(0x12345678); }
};

#define CV_TEST_MAIN(resourcesubdir, ...)                                                          \
    int main(int argc, char** argv)                                                                \
    {                                                                                              \
        ::testing::InitGoogleTest(&argc, argv);                                                    \
        ::testing::UnitTest::GetInstance()->listeners().Append(new RcmeReseedListener);            \
        return RUN_ALL_TESTS();                                                                    \
    }

#endif // OPENCV_RCME_TEST_STANDALONE_SHIM_HPP
