// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_CORE_HPP
#define OPENCV_RCME_GEOMETRY_CORE_HPP

// What the geometry needs: Eigen and OpenCV's core, not rcme's public headers (precomp.hpp), so
// that a change of the public API does not recompile it (ccache keys on the preprocessed input).

#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#endif // OPENCV_RCME_GEOMETRY_CORE_HPP
