// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "components/residual_uncertainty.hpp"

#include "geometry/epipolar.hpp"
#include "geometry/vector_clones.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// d^2 = r^2 / |J|^2 and the model's term a^T M a / |J|^2 of one correspondence; F row-major, C the
// first Rows rows of the 7 x 9 factor, row-major (the others are zero: they would add +0).
// Inlined into the one-point form and into each clone of the loop.
template <int Rows>
RCME_ALWAYS_INLINE void propagate(const double* f, const double* c, double x1, double y1, double x2,
                                  double y2, double& distanceSquared, double& modelTerm)
{
    const double l0 = f[0] * x1 + f[1] * y1 + f[2]; // F x1
    const double l1 = f[3] * x1 + f[4] * y1 + f[5];
    const double l2 = f[6] * x1 + f[7] * y1 + f[8];
    const double m0 = f[0] * x2 + f[3] * y2 + f[6]; // F^T x2, first two entries
    const double m1 = f[1] * x2 + f[4] * y2 + f[7];
    const double r = x2 * l0 + y2 * l1 + l2;
    const double jj = l0 * l0 + l1 * l1 + m0 * m0 + m1 * m1;
    const double a[9] = {x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x1, y1, 1.0};
    double quadratic = 0;
    // Unrolled, so that the loop over the points is the innermost one and vectorizes.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 7
#endif
    for (int k = 0; k < Rows; ++k) {
        double row = 0;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 9
#endif
        for (int j = 0; j < 9; ++j)
            row += c[9 * k + j] * a[j];
        quadratic += row * row;
    }
    // |J| = 0 (a point at an epipole): infinitely far, with the noise's variance alone.
    const bool defined = jj > 0;
    distanceSquared = defined ? r * r / jj : std::numeric_limits<double>::infinity();
    modelTerm = defined ? quadratic / jj : 0.0;
}

// The leverage-corrected variance of a sample point can round to or below zero when the model
// fits it exactly; a floor keeps the test statistic finite.
RCME_ALWAYS_INLINE double flooredVariance(double sigmaSquared, double modelTerm)
{
    const double floor = 1e-6 * sigmaSquared, variance = sigmaSquared + modelTerm;
    return floor < variance ? variance : floor;
}

template <int Rows>
RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
propagateLoop(const double* f, const double* c, const double* a, const double* b, size_t n,
              double sigmaSquared, double* distancesSquared, double* variances)
{
    // Local copies: the stores below cannot alias them, so they stay in registers.
    double fLocal[9], cLocal[Rows * 9];
    std::copy(f, f + 9, fLocal);
    std::copy(c, c + Rows * 9, cLocal);
    f = fLocal;
    c = cLocal;
    for (size_t i = 0; i < n; ++i) {
        double modelTerm = 0;
        propagate<Rows>(f, c, a[2 * i], a[2 * i + 1], b[2 * i], b[2 * i + 1], distancesSquared[i],
                        modelTerm);
        variances[i] = flooredVariance(sigmaSquared, modelTerm);
    }
}

// C with C^T C = D Sigma D^T into the first P rows of the 7 x 9 `factor` (row-major), the others
// zero. Sigma = P^T L D L^T P, so a^T D Sigma D^T a = |D^1/2 L^T P directions a|^2.
template <int P> void factorize(const TangentUncertainty<P>& uncertainty, double* factor)
{
    // Directions as rows: row k is vec(dF/dtheta_k), so that row k times a is g_k.
    Eigen::Matrix<double, P, 9> directions;
    for (int k = 0; k < P; ++k)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                directions(k, 3 * r + c) = uncertainty.directions[k](r, c);
    const Eigen::LDLT<Eigen::Matrix<double, P, P>> ldlt(uncertainty.covariance);
    const Eigen::Matrix<double, P, 9> permuted = ldlt.transpositionsP() * directions;
    Eigen::Map<Eigen::Matrix<double, 7, 9, Eigen::RowMajor>> rows(factor);
    rows.setZero();
    rows.template topRows<P>() =
        ldlt.vectorD().cwiseMax(0.0).cwiseSqrt().asDiagonal() * (ldlt.matrixU() * permuted);
}

} // namespace

ResidualUncertainty::ResidualUncertainty(const Model& model, double sigma)
    : sigmaSquared_(sigma * sigma)
{
    CV_Assert(model.uncertainty.isKnown());
    model.uncertainty.visitKnown([this](const auto& uncertainty) {
        factorize(uncertainty, factor_);
        rows_ = uncertainty.kDof;
    });
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> F(F_);
    F = model.F;
}

void ResidualUncertainty::evaluate(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                                   bool leverage, double& distanceSquared, double& variance) const
{
    double modelTerm = 0;
    if (rows_ == MotionUncertainty::kDof)
        propagate<MotionUncertainty::kDof>(F_, factor_, x1.x(), x1.y(), x2.x(), x2.y(),
                                           distanceSquared, modelTerm);
    else
        propagate<FundamentalUncertainty::kDof>(F_, factor_, x1.x(), x1.y(), x2.x(), x2.y(),
                                                distanceSquared, modelTerm);
    variance = flooredVariance(sigmaSquared_, leverage ? -modelTerm : modelTerm);
}

void ResidualUncertainty::evaluate(const Eigen::Vector2d* points1, const Eigen::Vector2d* points2,
                                   size_t count, double* distancesSquared, double* variances) const
{
    const auto loop = rows_ == MotionUncertainty::kDof
                          ? propagateLoop<MotionUncertainty::kDof>
                          : propagateLoop<FundamentalUncertainty::kDof>;
    loop(F_, factor_, points1->data(), points2->data(), count, sigmaSquared_, distancesSquared,
         variances);
}

} // namespace detail
} // namespace rcme
} // namespace cv
