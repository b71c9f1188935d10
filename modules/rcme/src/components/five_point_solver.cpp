// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model instantiation" of Fig. 1 with the 5-point algorithm for calibrated data (Nister
// 2004; in the Groebner-basis form of Stewenius, Engels & Nister 2006, "Recent developments on
// direct relative orientation"): 5 correspondences for the 5 DoF of E, so the sample is fitted
// exactly and the solver is not over-parameterized.
//
// In normalized camera coordinates q = K^-1 [x; 1], q2^T E q1 = 0 gives five linear equations
// on the nine entries of E, whose null space is E = x E1 + y E2 + z E3 + E4. The essential
// constraints det E = 0 and 2 E E^T E - tr(E E^T) E = 0 are ten cubics in (x, y, z) over the 20
// monomials of degree at most 3. In graded reverse lexicographic order (x > y > z) the ten
// cubic monomials lead; Gauss-Jordan elimination of the 10x20 coefficient matrix expresses each
// of them in the ten remaining monomials {x^2, xy, y^2, xz, yz, z^2, x, y, z, 1}, a basis of the
// quotient ring (generically ten solutions). Multiplication by x maps that basis into itself or
// into the eliminated monomials x^3, x^2y, xy^2, x^2z, xyz, xz^2, so it has a 10x10 matrix whose
// eigenvectors are the basis monomials evaluated at the solutions: (x, y, z, 1) is read from
// their last four entries. Each real root is then polished by a few Gauss-Newton steps on the
// ten constraints (close roots lose accuracy in the eigen decomposition: without the polish the
// singular values of E were (s, s, 0) only to ~1e-7 in 1 of 10^4 noise-free samples, with it to
// ~1e-15).

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"

#include <algorithm>
#include <array>

namespace cv {
namespace rcme {
namespace detail {

namespace {

constexpr int kMonomials = 20;

//! Exponents (of x, y, z) of the 20 monomials of degree <= 3, graded reverse lexicographic.
constexpr int kExponents[kMonomials][3] = {
    {3, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 3, 0}, {2, 0, 1}, {1, 1, 1},
    {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {0, 0, 3},                       // cubic: eliminated
    {2, 0, 0}, {1, 1, 0}, {0, 2, 0}, {1, 0, 1}, {0, 1, 1}, {0, 0, 2}, // quotient basis ...
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};

enum Monomial
{
    XXX = 0,
    XXY,
    XYY,
    YYY,
    XXZ,
    XYZ,
    YYZ,
    XZZ,
    YZZ,
    ZZZ,
    XX,
    XY,
    YY,
    XZ,
    YZ,
    ZZ,
    X,
    Y,
    Z,
    ONE
};

//! Index of the monomial x^a y^b z^c (a + b + c <= 3).
int monomialIndex(int a, int b, int c)
{
    for (int m = 0; m < kMonomials; ++m)
        if (kExponents[m][0] == a && kExponents[m][1] == b && kExponents[m][2] == c)
            return m;
    return -1;
}

//! Product table: kProduct[i][j] the index of monomial i times monomial j, -1 above degree 3.
struct ProductTable
{
    int index[kMonomials][kMonomials];
    ProductTable()
    {
        for (int i = 0; i < kMonomials; ++i)
            for (int j = 0; j < kMonomials; ++j) {
                const int a = kExponents[i][0] + kExponents[j][0];
                const int b = kExponents[i][1] + kExponents[j][1];
                const int c = kExponents[i][2] + kExponents[j][2];
                index[i][j] = a + b + c <= 3 ? monomialIndex(a, b, c) : -1;
            }
    }
};

const ProductTable& productTable()
{
    static const ProductTable table;
    return table;
}

//! A polynomial of degree <= 3 in (x, y, z): coefficients over the monomials above.
using Poly = std::array<double, kMonomials>;

Poly zeroPoly()
{
    Poly p;
    p.fill(0.0);
    return p;
}

//! p * q; the caller guarantees deg p + deg q <= 3.
Poly multiply(const Poly& p, const Poly& q)
{
    const ProductTable& table = productTable();
    Poly r = zeroPoly();
    for (int i = 0; i < kMonomials; ++i) {
        if (p[size_t(i)] == 0)
            continue;
        for (int j = 0; j < kMonomials; ++j) {
            if (q[size_t(j)] == 0)
                continue;
            const int k = table.index[i][j];
            CV_DbgAssert(k >= 0);
            if (k >= 0)
                r[size_t(k)] += p[size_t(i)] * q[size_t(j)];
        }
    }
    return r;
}

Poly operator+(Poly p, const Poly& q)
{
    for (size_t i = 0; i < p.size(); ++i)
        p[i] += q[i];
    return p;
}

Poly operator-(Poly p, const Poly& q)
{
    for (size_t i = 0; i < p.size(); ++i)
        p[i] -= q[i];
    return p;
}

Poly operator*(double s, Poly p)
{
    for (double& c : p)
        c *= s;
    return p;
}

/** The ten constraints of an essential matrix on E = x E1 + y E2 + z E3 + E4 as the rows of a
10x20 coefficient matrix (columns in monomial order). */
Eigen::Matrix<double, 10, kMonomials> essentialConstraints(const Eigen::Matrix3d basis[4])
{
    Poly E[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            Poly p = zeroPoly();
            p[X] = basis[0](r, c);
            p[Y] = basis[1](r, c);
            p[Z] = basis[2](r, c);
            p[ONE] = basis[3](r, c);
            E[r][c] = p;
        }
    Eigen::Matrix<double, 10, kMonomials> M;
    const auto setRow = [&M](int row, const Poly& p) {
        for (int m = 0; m < kMonomials; ++m)
            M(row, m) = p[size_t(m)];
    };
    // det E by the first row.
    const Poly det = multiply(E[0][0], multiply(E[1][1], E[2][2]) - multiply(E[1][2], E[2][1])) -
                     multiply(E[0][1], multiply(E[1][0], E[2][2]) - multiply(E[1][2], E[2][0])) +
                     multiply(E[0][2], multiply(E[1][0], E[2][1]) - multiply(E[1][1], E[2][0]));
    setRow(0, det);
    // E E^T (symmetric) and its trace.
    Poly EEt[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c) {
            EEt[r][c] = multiply(E[r][0], E[c][0]) + multiply(E[r][1], E[c][1]) +
                        multiply(E[r][2], E[c][2]);
            EEt[c][r] = EEt[r][c];
        }
    const Poly halfTrace = 0.5 * (EEt[0][0] + EEt[1][1] + EEt[2][2]);
    // E E^T E - tr(E E^T) E / 2 = 0 (the constraint halved).
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            Poly p = multiply(EEt[r][0], E[0][c]) + multiply(EEt[r][1], E[1][c]) +
                     multiply(EEt[r][2], E[2][c]) - multiply(halfTrace, E[r][c]);
            setRow(1 + 3 * r + c, p);
        }
    return M;
}

double power(double v, int e)
{
    double r = 1;
    for (int i = 0; i < e; ++i)
        r *= v;
    return r;
}

/** Gauss-Newton steps on the ten constraints M m(p) = 0 at p = (x, y, z): polishes a root that
the eigen decomposition found with reduced accuracy (close roots). A step is kept only when it
lowers the residual. */
void polishRoot(const Eigen::Matrix<double, 10, kMonomials>& M, Eigen::Vector3d& p)
{
    double residual = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best = p;
    for (int iteration = 0; iteration < 4; ++iteration) {
        Eigen::Matrix<double, kMonomials, 1> m;
        Eigen::Matrix<double, kMonomials, 3> dm;
        for (int k = 0; k < kMonomials; ++k) {
            const int a = kExponents[k][0], b = kExponents[k][1], c = kExponents[k][2];
            const double px = power(p.x(), a), py = power(p.y(), b), pz = power(p.z(), c);
            m(k) = px * py * pz;
            dm(k, 0) = a > 0 ? a * power(p.x(), a - 1) * py * pz : 0.0;
            dm(k, 1) = b > 0 ? b * px * power(p.y(), b - 1) * pz : 0.0;
            dm(k, 2) = c > 0 ? c * px * py * power(p.z(), c - 1) : 0.0;
        }
        const Eigen::Matrix<double, 10, 1> r = M * m;
        const double norm = r.norm();
        if (!(norm < residual))
            break;
        residual = norm;
        best = p;
        if (iteration == 3)
            break;
        const Eigen::Matrix<double, 10, 3> J = M * dm;
        const Eigen::Vector3d step = (J.transpose() * J).ldlt().solve(J.transpose() * r);
        if (!step.allFinite())
            break;
        p -= step;
    }
    p = best;
}

class FivePointSolver final : public MinimalSolver
{
public:
    int sampleSize() const override { return 5; }
    int maxSolutions() const override { return 10; }
    bool isOverParameterized() const override { return false; }
    std::unique_ptr<MinimalSolver> clone() const override
    {
        return std::make_unique<FivePointSolver>(*this);
    }

    int estimate(const TwoViewData& data, const std::vector<int>& sample,
                 std::vector<Model>& models) override
    {
        models.clear();
        // Calibrated data only (the factory never pairs this solver with uncalibrated data).
        if (!data.calibrated || sample.size() != 5)
            return 0;

        // q2^T E q1 = 0 as a row of A times the row-major entries of E, rows of unit norm; A is
        // padded with four zero rows so that the SVD gives the full null space.
        Eigen::Matrix<double, 9, 9> A = Eigen::Matrix<double, 9, 9>::Zero();
        for (int k = 0; k < 5; ++k) {
            const size_t i = static_cast<size_t>(sample[static_cast<size_t>(k)]);
            const Eigen::Vector3d a = data.Kinv * homogeneous(data.points1[i]);
            const Eigen::Vector3d b = data.Kinv * homogeneous(data.points2[i]);
            A.row(k) << b.x() * a.transpose(), b.y() * a.transpose(), b.z() * a.transpose();
            const double norm = A.row(k).norm();
            if (!(norm > 0) || !std::isfinite(norm))
                return 0;
            A.row(k) /= norm;
        }
        const Eigen::JacobiSVD<Eigen::Matrix<double, 9, 9>> svd(A, Eigen::ComputeFullV);
        const Eigen::Matrix<double, 9, 1> sv = svd.singularValues();
        // A fifth (near) null direction: coincident, collinear or otherwise degenerate points.
        if (!(sv(4) > 1e-7 * sv(0)))
            return 0;
        const Eigen::Matrix<double, 9, 9>& V = svd.matrixV();
        Eigen::Matrix3d basis[4];
        for (int b = 0; b < 4; ++b)
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    basis[b](r, c) = V(3 * r + c, 5 + b);

        Eigen::Matrix<double, 10, kMonomials> M = essentialConstraints(basis);
        for (int r = 0; r < 10; ++r) {
            const double norm = M.row(r).norm();
            if (!(norm > 0))
                return 0;
            M.row(r) /= norm;
        }
        // Gauss-Jordan: [L | R] -> [I | L^-1 R], each cubic monomial in terms of the basis.
        const Eigen::Matrix<double, 10, 10> L = M.leftCols<10>();
        const Eigen::FullPivLU<Eigen::Matrix<double, 10, 10>> lu(L);
        const Eigen::Matrix<double, 10, 10> Lu = lu.matrixLU();
        const double pivotMax = std::abs(Lu(0, 0)), pivotMin = std::abs(Lu(9, 9));
        if (!(pivotMin > 1e-12 * pivotMax))
            return 0;
        const Eigen::Matrix<double, 10, 10> G = lu.solve(M.rightCols<10>());
        if (!G.allFinite())
            return 0;

        // Action matrix of multiplication by x on the basis b = (x^2, xy, y^2, xz, yz, z^2, x,
        // y, z, 1): x b = Ax b. A cubic monomial m_i = -G.row(i) b.
        Eigen::Matrix<double, 10, 10> Ax = Eigen::Matrix<double, 10, 10>::Zero();
        Ax.row(0) = -G.row(XXX); // x * x^2
        Ax.row(1) = -G.row(XXY); // x * xy
        Ax.row(2) = -G.row(XYY); // x * y^2
        Ax.row(3) = -G.row(XXZ); // x * xz
        Ax.row(4) = -G.row(XYZ); // x * yz
        Ax.row(5) = -G.row(XZZ); // x * z^2
        Ax(6, XX - 10) = 1;      // x * x
        Ax(7, XY - 10) = 1;      // x * y
        Ax(8, XZ - 10) = 1;      // x * z
        Ax(9, X - 10) = 1;       // x * 1

        const Eigen::EigenSolver<Eigen::Matrix<double, 10, 10>> eigen(Ax, true);
        if (eigen.info() != Eigen::Success)
            return 0;
        const auto values = eigen.eigenvalues();
        const auto vectors = eigen.eigenvectors();
        for (int k = 0; k < 10; ++k) {
            // Real eigenvalues come from 1x1 blocks of the real Schur form: exactly real.
            if (values(k).imag() != 0)
                continue;
            // The eigenvector is real up to a complex factor: divide by its largest entry.
            int largest = 0;
            vectors.col(k).cwiseAbs().maxCoeff(&largest);
            const std::complex<double> phase = vectors(largest, k);
            if (phase == std::complex<double>(0))
                continue;
            double w[4];
            for (int j = 0; j < 4; ++j)
                w[j] = (vectors(6 + j, k) / phase).real(); // (x, y, z, 1) up to scale
            Eigen::Matrix3d E;
            if (std::abs(w[3]) >
                1e-8 * std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])})) {
                Eigen::Vector3d p(w[0] / w[3], w[1] / w[3], w[2] / w[3]);
                polishRoot(M, p);
                E = p.x() * basis[0] + p.y() * basis[1] + p.z() * basis[2] + basis[3];
            } else {
                // A root at (or near) infinity of the chart: E from the eigenvector alone.
                E = w[0] * basis[0] + w[1] * basis[1] + w[2] * basis[2] + w[3] * basis[3];
            }
            const double norm = E.norm();
            if (!(norm > 0) || !E.allFinite())
                continue;
            Model model;
            model.E = normalizeFundamental(E);
            model.F = fundamentalFromEssential(model.E, data.Kinv);
            if (!model.F.allFinite() || !model.E.allFinite())
                continue;
            // Two eigenvalues polished onto the same root (a double root) give one model.
            bool repeated = false;
            for (const Model& other : models)
                repeated = repeated || (other.E - model.E).norm() < 1e-12;
            if (!repeated)
                models.push_back(model);
        }
        return static_cast<int>(models.size());
    }
};

} // namespace

std::unique_ptr<MinimalSolver> createFivePointSolver()
{
    return std::make_unique<FivePointSolver>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
