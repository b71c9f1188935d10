// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_PERF_PRECOMP_HPP
#define OPENCV_RCME_PERF_PRECOMP_HPP

#ifdef RCME_GOOGLE_BENCHMARK
#include <benchmark/benchmark.h>
#else
#include "opencv2/ts.hpp"
#endif

#include "opencv2/rcme.hpp"

#include "opencv2/rcme/opencv_geometry.hpp"

#endif // OPENCV_RCME_PERF_PRECOMP_HPP
