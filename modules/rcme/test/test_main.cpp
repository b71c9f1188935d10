// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "test_precomp.hpp"

CV_TEST_MAIN("cv")
