// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Compiled with -fno-math-errno (modules/rcme/CMakeLists.txt): otherwise std::sqrt keeps a branch
// that sets errno for a negative argument, and a loop with a branch does not vectorize. The
// square root's value does not change.

#include "geometry/sampson_gradients.hpp"

#include "geometry/epipolar.hpp"
#include "geometry/vector_clones.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The per-point quantities every direction's gradient needs.
struct BlockTerms
{
    double f0[kSampsonBlock], f1[kSampsonBlock], t0[kSampsonBlock], t1[kSampsonBlock];
    double inverseNorm[kSampsonBlock], w[kSampsonBlock]; // 1 / |J| and d / |J|^2
};

// F x1 (rows 0 and 1), F^T x2 (rows 0 and 1), the residual r = x2^T F x1 and |J|^2 of one point.
// The sums in the order of sampsonDistanceAndGradient's Eigen products (the third row of a 3x3
// matrix times a vector is a0 + (a1 + a2); the other rows and the dot products left to right), so
// that both give the same bits; p.z() = 1 multiplies exactly. Inlined into each clone.
struct PointTerms
{
    double f0, f1, t0, t1, r, jj;
};

RCME_ALWAYS_INLINE PointTerms pointTerms(const double* f, double a, double b, double c, double e)
{
    PointTerms p;
    p.f0 = f[0] * a + f[1] * b + f[2];
    p.f1 = f[3] * a + f[4] * b + f[5];
    const double f2 = f[6] * a + (f[7] * b + f[8]);
    p.t0 = f[0] * c + f[3] * e + f[6];
    p.t1 = f[1] * c + f[4] * e + f[7];
    p.r = c * p.f0 + e * p.f1 + f2;
    p.jj = p.f0 * p.f0 + p.f1 * p.f1 + p.t0 * p.t0 + p.t1 * p.t1;
    return p;
}

RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
distancesOfBlock(const double* __restrict f, const double* __restrict x1,
                 const double* __restrict y1, const double* __restrict x2,
                 const double* __restrict y2, int count, BlockTerms& __restrict terms,
                 double* __restrict distance, uchar* __restrict valid)
{
    for (int i = 0; i < count; ++i) {
        const PointTerms p = pointTerms(f, x1[i], y1[i], x2[i], y2[i]);
        // Zero where J vanishes: the point's distance and gradients are then zeros.
        const double inverseNorm = p.jj > 0 ? 1.0 / std::sqrt(p.jj) : 0.0;
        valid[i] = p.jj > 0 ? 1 : 0;
        distance[i] = p.r * inverseNorm;
        terms.f0[i] = p.f0;
        terms.f1[i] = p.f1;
        terms.t0[i] = p.t0;
        terms.t1[i] = p.t1;
        terms.inverseNorm[i] = inverseNorm;
        terms.w[i] = distance[i] * inverseNorm * inverseNorm;
    }
}

// Each point's gradient over F's nine entries, then its dot product with each of the P
// directions (rows of `directions`, row-major entries).
template <int P>
RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
gradientsOfBlock(const double* __restrict directions, const double* __restrict x1,
                 const double* __restrict y1, const double* __restrict x2,
                 const double* __restrict y2, int count, const BlockTerms& __restrict terms,
                 double* __restrict gradients)
{
    for (int i = 0; i < count; ++i) {
        double entries[9];
        sampsonEntryGradient(x1[i], y1[i], x2[i], y2[i], terms.f0[i], terms.f1[i], terms.t0[i],
                             terms.t1[i], terms.inverseNorm[i], terms.w[i], entries);
        for (int k = 0; k < P; ++k)
            gradients[k * kSampsonBlock + i] = projectEntryGradient(directions + 9 * k, entries);
    }
}

RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
squaredDistancesOfBlock(const double* __restrict f, const double* __restrict x1,
                        const double* __restrict y1, const double* __restrict x2,
                        const double* __restrict y2, int count, double* __restrict out)
{
    for (int i = 0; i < count; ++i) {
        const PointTerms p = pointTerms(f, x1[i], y1[i], x2[i], y2[i]);
        out[i] = p.jj > 0 ? p.r * p.r / p.jj : std::numeric_limits<double>::infinity();
    }
}

// The points are interleaved (x, y) pairs, as TwoViewData holds them.
RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
withinDistanceLoop(const double* __restrict f, const double* __restrict a,
                   const double* __restrict b, size_t count, double thresholdSquared,
                   uchar* __restrict within)
{
    for (size_t i = 0; i < count; ++i) {
        const PointTerms p = pointTerms(f, a[2 * i], a[2 * i + 1], b[2 * i], b[2 * i + 1]);
        const double squared =
            p.jj > 0 ? p.r * p.r / p.jj : std::numeric_limits<double>::infinity();
        within[i] = squared < thresholdSquared ? 1 : 0;
    }
}

// sum_j a[j] b[j] over j < count in four partial sums (point j into sum j % 4; the AVX2 clone
// holds them in one register), added as (s0 + s1) + (s2 + s3): the order is the source's, so both
// clones give the same bits.
RCME_ALWAYS_INLINE double dotInLanes(const double* __restrict a, const double* __restrict b,
                                     int count)
{
    double s[4] = {0.0, 0.0, 0.0, 0.0};
    int j = 0;
    for (; j + 4 <= count; j += 4)
        for (int l = 0; l < 4; ++l)
            s[l] += a[j + l] * b[j + l];
    for (int l = 0; j + l < count; ++l)
        s[l] += a[j + l] * b[j + l];
    return (s[0] + s[1]) + (s[2] + s[3]);
}

// The upper triangle of J^T J and J^T r, an entry at a time over the block's points. An invalid
// point's distance and gradients are zeros (distancesOfBlock): it adds nothing.
template <int P>
RCME_VECTOR_CLONES void normalEquationsLoop(const double* __restrict distance,
                                            const double* __restrict gradients, int count,
                                            double* __restrict normal)
{
    for (int a = 0; a < P; ++a) {
        const double* ga = gradients + a * kSampsonBlock;
        for (int b = a; b < P; ++b)
            normal[a * (P + 1) + b] += dotInLanes(ga, gradients + b * kSampsonBlock, count);
        normal[a * (P + 1) + P] += dotInLanes(ga, distance, count);
    }
}

void rowMajor(const Eigen::Matrix3d& M, double* out)
{
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            out[3 * r + c] = M(r, c);
}

} // namespace

void sampsonGradientsOfBlock(const Eigen::Matrix3d& F, const Eigen::Matrix3d* directions,
                             int parameters, const double* x1, const double* y1, const double* x2,
                             const double* y2, int count, double* distance, double* gradients,
                             uchar* valid)
{
    CV_DbgAssert(count <= kSampsonBlock && parameters <= 7);
    BlockTerms terms;
    double f[9];
    rowMajor(F, f);
    distancesOfBlock(f, x1, y1, x2, y2, count, terms, distance, valid);
    if (parameters != 5 && parameters != 7)
        CV_Error(Error::StsNotImplemented, "Sampson gradients of 5 or 7 parameters only");
    double rows[7 * 9];
    for (int k = 0; k < parameters; ++k)
        rowMajor(directions[k], rows + 9 * k);
    if (parameters == 5)
        gradientsOfBlock<5>(rows, x1, y1, x2, y2, count, terms, gradients);
    else
        gradientsOfBlock<7>(rows, x1, y1, x2, y2, count, terms, gradients);
}

void sampsonDistancesSquaredOfBlock(const Eigen::Matrix3d& F, const double* x1, const double* y1,
                                    const double* x2, const double* y2, int count,
                                    double* distanceSquared)
{
    CV_DbgAssert(count <= kSampsonBlock);
    double f[9];
    rowMajor(F, f);
    squaredDistancesOfBlock(f, x1, y1, x2, y2, count, distanceSquared);
}

void accumulateNormalEquations(int parameters, const double* distance, const double* gradients,
                               int count, double* normal)
{
    CV_DbgAssert(count <= kSampsonBlock);
    if (parameters == 5)
        normalEquationsLoop<5>(distance, gradients, count, normal);
    else if (parameters == 7)
        normalEquationsLoop<7>(distance, gradients, count, normal);
    else
        CV_Error(Error::StsNotImplemented, "normal equations of 5 or 7 parameters only");
}

void markWithinSampsonDistance(const Eigen::Matrix3d& F,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                               std::vector<uchar>& within)
{
    CV_DbgAssert(points1.size() == points2.size());
    within.resize(points1.size());
    if (points1.empty())
        return;
    double f[9];
    rowMajor(F, f);
    withinDistanceLoop(f, points1.data()->data(), points2.data()->data(), points1.size(),
                       thresholdSquared, within.data());
}

} // namespace detail
} // namespace rcme
} // namespace cv
