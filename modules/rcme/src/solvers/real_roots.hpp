// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_REAL_ROOTS_HPP
#define OPENCV_RCME_SOLVERS_REAL_ROOTS_HPP

namespace cv {
namespace rcme {
namespace detail {

//! The largest degree realRoots accepts.
constexpr int kMaxRootDegree = 10;

/** The distinct real roots of p(x) = coefficients[0] + coefficients[1] x + ... +
coefficients[degree] x^degree, degree <= kMaxRootDegree, in increasing order; returns their number.
Sturm sequences isolate each root, then safeguarded Newton steps polish it to machine precision:
no allocation, no eigen decomposition, a few hundred flops per root. Leading coefficients that are
negligible next to the largest one are dropped (their roots are at infinity). */
int realRoots(const double* coefficients, int degree, double* roots);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
