// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Nister's five-point algorithm (2004). Five equations q2^T E q1 = 0 leave a 4-dimensional null
// space, E = x X + y Y + z Z + W. The essential constraints det E = 0 and
// 2 E E^T E - tr(E E^T) E = 0 are ten cubics in (x, y, z) over 20 monomials. Gauss-Jordan
// elimination of their 10x20 coefficient matrix, with Nister's monomial order, expresses ten of
// the monomials (x^3 ... xy) in the ten others. Three differences of the eliminated rows,
// <x^2 z> - z <x^2>, <y^2 z> - z <y^2> and <xyz> - z <xy>, then hold only x, y and 1 with
// coefficients polynomial in z: B(z) [x y 1]^T = 0, so det B(z), of degree 10, vanishes at every
// solution. Its real roots come from Sturm sequences (solvers/real_roots.cpp), x and y from the
// null vector of B(z), and a few Gauss-Newton steps on the ten cubics polish each root (close
// roots lose accuracy in the elimination).

#include "solvers/essential_five_point.hpp"

#include "solvers/epipolar_null_space.hpp"
#include "solvers/real_roots.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Exponents of x, y, z. The cubic monomials in Nister's order: the ten eliminated first, then
// the ten that remain (their coefficients G after the elimination).
constexpr int kMonomials = 20;
constexpr int kCubicExponents[kMonomials][3] = {
    {3, 0, 0}, {0, 3, 0}, {2, 1, 0}, {1, 2, 0}, {2, 0, 1}, {2, 0, 0},
    {0, 2, 1}, {0, 2, 0}, {1, 1, 1}, {1, 1, 0},                       // eliminated
    {1, 0, 2}, {1, 0, 1}, {1, 0, 0}, {0, 1, 2}, {0, 1, 1}, {0, 1, 0}, // x z^2 ... y
    {0, 0, 3}, {0, 0, 2}, {0, 0, 1}, {0, 0, 0}};                      // z^3 ... 1
constexpr int kQuadraticExponents[10][3] = {{2, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1},
                                            {0, 0, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
constexpr int kLinearExponents[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};

// Rows of the eliminated monomials that Nister's three differences pair: <a> - z <b>.
constexpr int kPairs[3][2] = {{4, 5}, {6, 7}, {8, 9}};

template <int N> constexpr int indexOf(const int (&exponents)[N][3], int a, int b, int c)
{
    for (int m = 0; m < N; ++m)
        if (exponents[m][0] == a && exponents[m][1] == b && exponents[m][2] == c)
            return m;
    return -1;
}

//! Where the product of two monomials lands: linear x linear, quadratic x linear.
struct ProductIndices
{
    int linearLinear[4][4];
    int quadraticLinear[10][4];
};

constexpr ProductIndices makeProductIndices()
{
    ProductIndices p{};
    for (int j = 0; j < 4; ++j) {
        const int* b = kLinearExponents[j];
        for (int i = 0; i < 4; ++i) {
            const int* a = kLinearExponents[i];
            p.linearLinear[i][j] =
                indexOf(kQuadraticExponents, a[0] + b[0], a[1] + b[1], a[2] + b[2]);
        }
        for (int i = 0; i < 10; ++i) {
            const int* a = kQuadraticExponents[i];
            p.quadraticLinear[i][j] =
                indexOf(kCubicExponents, a[0] + b[0], a[1] + b[1], a[2] + b[2]);
        }
    }
    return p;
}

constexpr ProductIndices kProducts = makeProductIndices();

using Linear = Eigen::Matrix<double, 4, 1>;
using Quadratic = Eigen::Matrix<double, 10, 1>;
using Cubic = Eigen::Matrix<double, kMonomials, 1>;

//! a b for a polynomial a (coefficients over A monomials) times a linear one, `where[i][j]` the
//! index of monomial i times monomial j among the N monomials of the product.
template <int N, int A>
Eigen::Matrix<double, N, 1> multiplyByLinear(const Eigen::Matrix<double, A, 1>& a, const Linear& b,
                                             const int (&where)[A][4])
{
    Eigen::Matrix<double, N, 1> product = Eigen::Matrix<double, N, 1>::Zero();
    for (int i = 0; i < A; ++i)
        for (int j = 0; j < 4; ++j)
            product(where[i][j]) += a(i) * b(j);
    return product;
}

Quadratic multiply(const Linear& a, const Linear& b)
{
    return multiplyByLinear<10>(a, b, kProducts.linearLinear);
}

Cubic multiply(const Quadratic& a, const Linear& b)
{
    return multiplyByLinear<kMonomials>(a, b, kProducts.quadraticLinear);
}

/** The ten cubic constraints on E = x X + y Y + z Z + W as the rows of a 10x20 matrix, each row
of unit norm: det E, then E E^T E - tr(E E^T) E / 2 entry by entry. */
Eigen::Matrix<double, 10, kMonomials> essentialConstraints(const Eigen::Matrix<double, 9, 4>& basis)
{
    Linear E[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            E[r][c] = basis.row(3 * r + c).transpose();
    Eigen::Matrix<double, 10, kMonomials> M;
    // det E along the first row.
    const Quadratic minor0 = multiply(E[1][1], E[2][2]) - multiply(E[1][2], E[2][1]);
    const Quadratic minor1 = multiply(E[1][0], E[2][2]) - multiply(E[1][2], E[2][0]);
    const Quadratic minor2 = multiply(E[1][0], E[2][1]) - multiply(E[1][1], E[2][0]);
    M.row(0) = (multiply(minor0, E[0][0]) - multiply(minor1, E[0][1]) + multiply(minor2, E[0][2]))
                   .transpose();
    Quadratic EEt[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c) {
            EEt[r][c] = multiply(E[r][0], E[c][0]) + multiply(E[r][1], E[c][1]) +
                        multiply(E[r][2], E[c][2]);
            EEt[c][r] = EEt[r][c];
        }
    const Quadratic halfTrace = 0.5 * (EEt[0][0] + EEt[1][1] + EEt[2][2]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            M.row(1 + 3 * r + c) = (multiply(EEt[r][0], E[0][c]) + multiply(EEt[r][1], E[1][c]) +
                                    multiply(EEt[r][2], E[2][c]) - multiply(halfTrace, E[r][c]))
                                       .transpose();
    for (int r = 0; r < 10; ++r) {
        const double norm = M.row(r).norm();
        if (norm > 0)
            M.row(r) /= norm;
    }
    return M;
}

/** Gauss-Jordan elimination with partial pivoting, [L | R] -> [I | G]: each of the first ten
monomials as minus G times the last ten. False when a pivot vanishes next to the largest one
(the constraints do not determine the elimination). Written out: Eigen's LU solve of a 10x10
system with ten right-hand sides takes its general matrix-product path, twice as slow here. */
bool eliminate(const Eigen::Matrix<double, 10, kMonomials>& M, Eigen::Matrix<double, 10, 10>& G)
{
    Eigen::Matrix<double, 10, kMonomials, Eigen::RowMajor> A = M;
    double largestPivot = 0;
    for (int col = 0; col < 10; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 10; ++r)
            if (std::abs(A(r, col)) > std::abs(A(pivot, col)))
                pivot = r;
        const double magnitude = std::abs(A(pivot, col));
        largestPivot = std::max(largestPivot, magnitude);
        if (!(magnitude > 1e-12 * largestPivot))
            return false;
        if (pivot != col)
            A.row(pivot).swap(A.row(col));
        A.row(col) /= A(col, col);
        for (int r = 0; r < 10; ++r)
            if (r != col && A(r, col) != 0)
                A.row(r) -= A(r, col) * A.row(col);
    }
    G = A.rightCols<10>();
    return G.allFinite();
}

//! c = a b for polynomials in z, coefficients ascending.
template <int A, int B>
Eigen::Matrix<double, A + B - 1, 1> multiplyInZ(const Eigen::Matrix<double, A, 1>& a,
                                                const Eigen::Matrix<double, B, 1>& b)
{
    Eigen::Matrix<double, A + B - 1, 1> c = Eigen::Matrix<double, A + B - 1, 1>::Zero();
    for (int i = 0; i < A; ++i)
        for (int j = 0; j < B; ++j)
            c(i + j) += a(i) * b(j);
    return c;
}

/** B(z) of Nister's hidden-variable step, from the eliminated rows G (each eliminated monomial
m_i = -G.row(i) times the remaining ones): row k is <a> - z <b> of pair k, its columns the
coefficients of x and y (cubics in z) and of 1 (a quartic). */
struct HiddenVariableMatrix
{
    Eigen::Matrix<double, 4, 1> x[3], y[3];
    Eigen::Matrix<double, 5, 1> one[3];

    explicit HiddenVariableMatrix(const Eigen::Matrix<double, 10, 10>& G)
    {
        for (int k = 0; k < 3; ++k) {
            const auto a = G.row(kPairs[k][0]), b = G.row(kPairs[k][1]);
            // Columns of G: x z^2, x z, x, y z^2, y z, y, z^3, z^2, z, 1.
            x[k] << a(2), a(1) - b(2), a(0) - b(1), -b(0);
            y[k] << a(5), a(4) - b(5), a(3) - b(4), -b(3);
            one[k] << a(9), a(8) - b(9), a(7) - b(8), a(6) - b(7), -b(6);
        }
    }

    Eigen::Matrix<double, 11, 1> determinant() const
    {
        const Eigen::Matrix<double, 8, 1> minor0 =
            multiplyInZ(y[1], one[2]) - multiplyInZ(one[1], y[2]);
        const Eigen::Matrix<double, 8, 1> minor1 =
            multiplyInZ(x[1], one[2]) - multiplyInZ(one[1], x[2]);
        const Eigen::Matrix<double, 7, 1> minor2 =
            multiplyInZ(x[1], y[2]) - multiplyInZ(y[1], x[2]);
        return multiplyInZ(x[0], minor0) - multiplyInZ(y[0], minor1) + multiplyInZ(one[0], minor2);
    }

    Eigen::Matrix3d at(double z) const
    {
        const auto horner = [z](const auto& p) {
            double value = 0;
            for (int i = static_cast<int>(p.size()) - 1; i >= 0; --i)
                value = value * z + p(i);
            return value;
        };
        Eigen::Matrix3d B;
        for (int k = 0; k < 3; ++k)
            B.row(k) << horner(x[k]), horner(y[k]), horner(one[k]);
        return B;
    }
};

//! The 20 monomials at p and their derivatives.
void monomials(const Eigen::Vector3d& p, Eigen::Matrix<double, kMonomials, 1>& m,
               Eigen::Matrix<double, kMonomials, 3>& dm)
{
    double powers[3][4];
    for (int v = 0; v < 3; ++v) {
        powers[v][0] = 1;
        for (int e = 1; e < 4; ++e)
            powers[v][e] = powers[v][e - 1] * p(v);
    }
    for (int k = 0; k < kMonomials; ++k) {
        const int* e = kCubicExponents[k];
        const double px = powers[0][e[0]], py = powers[1][e[1]], pz = powers[2][e[2]];
        m(k) = px * py * pz;
        dm(k, 0) = e[0] > 0 ? e[0] * powers[0][e[0] - 1] * py * pz : 0.0;
        dm(k, 1) = e[1] > 0 ? e[1] * px * powers[1][e[1] - 1] * pz : 0.0;
        dm(k, 2) = e[2] > 0 ? e[2] * px * py * powers[2][e[2] - 1] : 0.0;
    }
}

/** Gauss-Newton steps on the ten constraints M m(p) = 0 at p = (x, y, z), each kept only when it
lowers the residual. Without them the singular values of E were (s, s, 0) only to ~1e-7 in 1
of 10^4 noise-free samples (close roots), with them to ~1e-15. */
void polishRoot(const Eigen::Matrix<double, 10, kMonomials>& M, Eigen::Vector3d& p)
{
    constexpr int kSteps = 8;
    Eigen::Matrix<double, kMonomials, 1> m;
    Eigen::Matrix<double, kMonomials, 3> dm;
    monomials(p, m, dm);
    Eigen::Matrix<double, 10, 1> r = M * m;
    double residual = r.norm();
    // Already at the arithmetic's floor (the usual case): nothing to gain.
    const double floor = 1e-15 * m.norm();
    for (int step = 0; step < kSteps && residual > floor; ++step) {
        const Eigen::Matrix<double, 10, 3> J = M * dm;
        const Eigen::Vector3d delta = (J.transpose() * J).ldlt().solve(J.transpose() * r);
        if (!delta.allFinite())
            return;
        const Eigen::Vector3d next = p - delta;
        monomials(next, m, dm);
        r = M * m;
        const double nextResidual = r.norm();
        if (!(nextResidual < residual))
            return;
        p = next;
        residual = nextResidual;
    }
}

} // namespace

int essentialFromFivePoints(const Eigen::Vector3d* q1, const Eigen::Vector3d* q2,
                            Eigen::Matrix3d* solutions)
{
    // A fifth (near) null direction: coincident, collinear or otherwise degenerate points.
    Eigen::Matrix<double, 9, 4> basis; // X, Y, Z, W
    if (!epipolarNullSpace<5>(q1, q2, 1e-7, basis))
        return 0;

    const Eigen::Matrix<double, 10, kMonomials> M = essentialConstraints(basis);
    Eigen::Matrix<double, 10, 10> G;
    if (!eliminate(M, G))
        return 0;

    const HiddenVariableMatrix B(G);
    const Eigen::Matrix<double, 11, 1> polynomial = B.determinant();
    double roots[kMaxRootDegree];
    const int rootCount = realRoots(polynomial.data(), 10, roots);
    int count = 0;
    for (int k = 0; k < rootCount; ++k) {
        const double z = roots[k];
        // [x y 1] spans the null space of B(z): the largest cross product of two of its rows.
        const Eigen::Matrix3d Bz = B.at(z);
        Eigen::Vector3d v = Bz.row(0).cross(Bz.row(1));
        for (const Eigen::Vector3d& w : {Eigen::Vector3d(Bz.row(0).cross(Bz.row(2))),
                                         Eigen::Vector3d(Bz.row(1).cross(Bz.row(2)))})
            if (w.squaredNorm() > v.squaredNorm())
                v = w;
        if (!(std::abs(v.z()) > 1e-12 * v.norm()))
            continue;
        Eigen::Vector3d p(v.x() / v.z(), v.y() / v.z(), z);
        polishRoot(M, p);
        Eigen::Matrix3d E;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                E(r, c) = basis.row(3 * r + c).dot(Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0));
        const double norm = E.norm();
        if (!(norm > 0) || !E.allFinite())
            continue;
        solutions[count++] = E / norm;
    }
    return count;
}

} // namespace detail
} // namespace rcme
} // namespace cv
