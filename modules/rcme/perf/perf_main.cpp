// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "perf_precomp.hpp"

#ifdef RCME_GOOGLE_BENCHMARK
BENCHMARK_MAIN();
#else
CV_PERF_TEST_MAIN(rcme)
#endif
