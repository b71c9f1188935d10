// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_SOLVERS_EPIPOLAR_NULL_SPACE_HPP
#define OPENCV_RCME_SOLVERS_EPIPOLAR_NULL_SPACE_HPP

#include <Eigen/Core>
#include <Eigen/QR>

#include <cmath>
#include <utility>

namespace cv {
namespace rcme {
namespace detail {

/** The epipolar equation x2^T F x1 = 0 of one correspondence as 9 coefficients over the
row-major entries of F, scaled to unit norm. False when they are zero or not finite. */
inline bool unitEpipolarEquation(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                 double* coefficients)
{
    Eigen::Map<Eigen::Matrix<double, 9, 1>> row(coefficients);
    for (int r = 0; r < 3; ++r)
        row.template segment<3>(3 * r) = x2(r) * x1;
    const double norm = row.norm();
    if (!(norm > 0) || !std::isfinite(norm))
        return false;
    row /= norm;
    return true;
}

/** The null space of the M epipolar equations x2[k]^T F x1[k] = 0 (M = 5, 7 or 8), each a row
of a Mx9 matrix A over the row-major entries of F, scaled to unit norm: the last 9 - M columns of
Q in the QR decomposition (column pivoting) of A^T, orthonormal. False when the equations are
not independent: |R(M-1, M-1)| / |R(0, 0)|, an estimate of A's smallest to largest singular
value, at most `rankTolerance` (coincident, collinear or otherwise degenerate points). A third of
the cost of the SVD of A or of the eigen decomposition of A^T A, which the solvers used before;
the 5-point solver's (the 7- and 8-point solvers take epipolarNullSpaceByElimination below). */
template <int M>
bool epipolarNullSpace(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2, double rankTolerance,
                       Eigen::Matrix<double, 9, 9 - M>& basis)
{
    Eigen::Matrix<double, 9, M> At;
    for (int k = 0; k < M; ++k)
        if (!unitEpipolarEquation(x1[k], x2[k], At.col(k).data()))
            return false;
    const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 9, M>> qr(At);
    if (!(std::abs(qr.matrixQR()(M - 1, M - 1)) > rankTolerance * std::abs(qr.matrixQR()(0, 0))))
        return false;
    // Q's last columns: the Householder reflections applied to the last unit vectors only.
    basis.setZero();
    basis.template bottomRows<9 - M>().setIdentity();
    basis.applyOnTheLeft(qr.householderQ());
    return basis.allFinite();
}

/** The same null space by Gaussian elimination with full pivoting on the Mx9 matrix A (each row
scaled to unit norm): the basis solves A x = 0 with each free entry in turn 1, then is made
orthonormal. False when the equations are not independent: the last pivot at most
`rankTolerance` times the first. The 7- and 8-point solvers' (a fraction of the QR's cost); the
5-point solver keeps the QR, whose answers with K the benchmark reports (doc/performance.md,
"The loop's own cost"). */
template <int M>
bool epipolarNullSpaceByElimination(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                                    double rankTolerance, Eigen::Matrix<double, 9, 9 - M>& basis)
{
    double A[M][9];
    for (int k = 0; k < M; ++k)
        if (!unitEpipolarEquation(x1[k], x2[k], A[k]))
            return false;
    int column[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8}; // column[j]: the entry of F in place j
    double firstPivot = 0;
    for (int k = 0; k < M; ++k) {
        // The largest entry by conditional moves (a branch per entry, taken at random, costs
        // more); the first of equal entries wins.
        int bestRow = k, bestCol = k;
        double best = 0;
        for (int i = k; i < M; ++i)
            for (int j = k; j < 9; ++j) {
                const double magnitude = std::abs(A[i][j]);
                const bool larger = magnitude > best;
                best = larger ? magnitude : best;
                bestRow = larger ? i : bestRow;
                bestCol = larger ? j : bestCol;
            }
        if (k == 0)
            firstPivot = best;
        if (!(best > rankTolerance * firstPivot))
            return false;
        if (bestRow != k)
            for (int j = 0; j < 9; ++j)
                std::swap(A[k][j], A[bestRow][j]);
        if (bestCol != k) {
            for (int i = 0; i < M; ++i)
                std::swap(A[i][k], A[i][bestCol]);
            std::swap(column[k], column[bestCol]);
        }
        for (int i = k + 1; i < M; ++i) {
            const double factor = A[i][k] / A[k][k];
            for (int j = k; j < 9; ++j)
                A[i][j] -= factor * A[k][j];
        }
    }
    // Back substitution for every free entry at once, x[j][f] the solution whose free entry f is
    // 1: a row of x is then read whole where it was written whole (solved one after the other,
    // each solution's entries were written one at a time and read two at a time, and every read
    // waited for the store). Each lane's arithmetic is that of its own solution. The 8-point
    // solver's one solution takes two lanes too, the second unused: its time was the same with one
    // (solver/8-point 733-739 ns before, 727-749 after).
    constexpr int kLanes = 9 - M < 2 ? 2 : 9 - M;
    double x[9][kLanes] = {};
    for (int f = 0; f < 9 - M; ++f)
        x[M + f][f] = 1;
    for (int k = M - 1; k >= 0; --k) {
        double sum[kLanes] = {};
        for (int j = k + 1; j < 9; ++j)
            for (int f = 0; f < kLanes; ++f)
                sum[f] += A[k][j] * x[j][f];
        for (int f = 0; f < kLanes; ++f)
            x[k][f] = -sum[f] / A[k][k];
    }
    for (int f = 0; f < 9 - M; ++f)
        for (int j = 0; j < 9; ++j)
            basis(column[j], f) = x[j][f];
    // Gram-Schmidt, twice for the accuracy of Householder's orthonormal columns.
    for (int f = 0; f < 9 - M; ++f) {
        for (int pass = 0; pass < 2; ++pass)
            for (int g = 0; g < f; ++g)
                basis.col(f) -= basis.col(g).dot(basis.col(f)) * basis.col(g);
        basis.col(f).normalize();
    }
    return basis.allFinite();
}

} // namespace detail
} // namespace rcme
} // namespace cv

#endif
