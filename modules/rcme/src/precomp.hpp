// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_PRECOMP_HPP
#define OPENCV_RCME_PRECOMP_HPP

// Only public OpenCV headers: Debian installs no opencv2/core/private.hpp.
#include "opencv2/rcme.hpp"

#include "opencv2/rcme/opencv_geometry.hpp"
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#endif // OPENCV_RCME_PRECOMP_HPP
