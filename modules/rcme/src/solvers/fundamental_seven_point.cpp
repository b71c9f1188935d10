// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "solvers/fundamental_seven_point.hpp"

#include "solvers/epipolar_null_space.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <opencv2/core/base.hpp>

#include <algorithm>
#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

namespace {

//! The adjugate's rows are cross products of the columns: adj(A) A = det(A) I.
Eigen::Matrix3d adjugate(const Eigen::Matrix3d& A)
{
    Eigen::Matrix3d adj;
    adj.row(0) = A.col(1).cross(A.col(2)).transpose();
    adj.row(1) = A.col(2).cross(A.col(0)).transpose();
    adj.row(2) = A.col(0).cross(A.col(1)).transpose();
    return adj;
}

/** Real roots of x^3 + b x^2 + c x + d (at most three, written to `roots`; returns how many).
Closed form on the depressed cubic, then Newton steps on the original polynomial for accuracy.
A discriminant within rounding of zero is read as a double root rather than a complex pair, so
that a double root is not lost. */
int solveMonicCubic(double b, double c, double d, double roots[3])
{
    const double shift = b / 3;
    const double p = c - b * shift;                       // y^3 + p y + q, x = y - b/3
    const double q = (2 * shift * shift - c) * shift + d; // 2b^3/27 - bc/3 + d
    const double halfQ = q / 2, thirdP = p / 3;
    const double disc = halfQ * halfQ + thirdP * thirdP * thirdP;
    const double scale = halfQ * halfQ + std::abs(thirdP * thirdP * thirdP);
    int count = 0;
    if (disc > 1e-12 * scale) {
        // One real root; u^3 chosen without cancellation, y = u - p / (3u).
        const double u = std::cbrt(-halfQ - std::copysign(std::sqrt(disc), halfQ));
        roots[count++] = (u != 0 ? u - thirdP / u : 0.0) - shift;
    } else if (thirdP < 0) {
        // Three real roots (two of them possibly equal): y = 2 r cos(phi/3 - 2 pi k/3).
        const double r = std::sqrt(-thirdP);
        const double cosPhi = std::max(-1.0, std::min(1.0, -halfQ / (r * r * r)));
        const double phi = std::acos(cosPhi);
        for (int k = 0; k < 3; ++k)
            roots[count++] = 2 * r * std::cos((phi - 2 * CV_PI * k) / 3) - shift;
    } else {
        roots[count++] = -shift; // p = q = 0: a triple root
    }
    for (int i = 0; i < count; ++i) {
        double x = roots[i];
        double value = ((x + b) * x + c) * x + d;
        for (int step = 0; step < 3 && value != 0; ++step) {
            const double slope = (3 * x + 2 * b) * x + c;
            if (slope == 0)
                break;
            const double next = x - value / slope;
            const double nextValue = ((next + b) * next + c) * next + d;
            if (!(std::abs(nextValue) < std::abs(value)))
                break;
            x = next;
            value = nextValue;
        }
        roots[i] = x;
    }
    // Drop repeats (a double root gives the same F twice).
    int unique = 0;
    for (int i = 0; i < count; ++i) {
        bool repeated = false;
        for (int j = 0; j < unique; ++j)
            repeated =
                repeated || std::abs(roots[i] - roots[j]) <= 1e-12 * (1 + std::abs(roots[j]));
        if (!repeated)
            roots[unique++] = roots[i];
    }
    return unique;
}

} // namespace

int fundamentalFromSevenPoints(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                               Eigen::Matrix3d* solutions)
{
    // A third (near) null direction means the sample does not determine the pencil:
    // coincident, collinear or otherwise degenerate points (the 8-point solver's tolerance).
    Eigen::Matrix<double, 9, 2> pencil;
    if (!epipolarNullSpaceByElimination<7>(x1, x2, 1e-5, pencil))
        return 0;
    Eigen::Matrix3d F1, F2;
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) {
            F1(r, col) = pencil(3 * r + col, 0);
            F2(r, col) = pencil(3 * r + col, 1);
        }
    // det(a F1 + (1 - a) F2) = 0 is a cubic on the pencil, but in that parameterization a
    // root can sit at (or near) infinity, where the leading coefficient vanishes. Instead the
    // pencil is written Fb + x Fa with Fa the member of largest |det| among four directions
    // 45 degrees apart (F1, F2 orthonormal): Fa is then no root, every root x is finite, and
    // the leading coefficient det(Fa) is the largest of the four samples, so the cubic is
    // well scaled (the four samples determine its four coefficients).
    double bestDet = 0, bestAngle = 0;
    for (int k = 0; k < 4; ++k) {
        const double angle = k * CV_PI / 4;
        const double det = (std::cos(angle) * F1 + std::sin(angle) * F2).determinant();
        if (std::abs(det) > std::abs(bestDet)) {
            bestDet = det;
            bestAngle = angle;
        }
    }
    // Every member singular (e.g. F1 and F2 share an epipole): the sample does not determine
    // F. Members have unit norm, so |det| is at most 3^-1.5.
    if (!(std::abs(bestDet) > 1e-12))
        return 0;
    const double c = std::cos(bestAngle), s = std::sin(bestAngle);
    const Eigen::Matrix3d Fa = c * F1 + s * F2, Fb = c * F2 - s * F1;
    // For 3x3: det(B + x A) = det B + x tr(adj(B) A) + x^2 tr(adj(A) B) + x^3 det A.
    const double c0 = Fb.determinant();
    const double c1 = (adjugate(Fb) * Fa).trace();
    const double c2 = (adjugate(Fa) * Fb).trace();
    const double c3 = Fa.determinant();
    double roots[3];
    const int rootCount = solveMonicCubic(c2 / c3, c1 / c3, c0 / c3, roots);
    for (int r = 0; r < rootCount; ++r)
        solutions[r] = Fb + roots[r] * Fa;
    return rootCount;
}

} // namespace detail
} // namespace rcme
} // namespace cv
