// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "geometry/residual_bands.hpp"
#include "geometry/vector_clones.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// F's entries (row-major) as values of the loop's own, so that no store of the loop (a mask) can
// alias them and they stay in registers.
struct FundamentalEntries
{
    double f00, f01, f02, f10, f11, f12, f20, f21, f22;
    explicit FundamentalEntries(const double* f)
        : f00(f[0]), f01(f[1]), f02(f[2]), f10(f[3]), f11(f[4]), f12(f[5]), f20(f[6]), f21(f[7]),
          f22(f[8])
    {
    }
};

// The two parts of point i's squared Sampson distance to F, rr / jj: rr = (x2^T F x1)^2 and jj
// the squared norm of its gradient in the four coordinates (zero at an epipole).
RCME_ALWAYS_INLINE void sampsonParts(const FundamentalEntries& F, const double* a, const double* b,
                                     size_t i, double& rr, double& jj)
{
    const double x1 = a[2 * i], y1 = a[2 * i + 1], x2 = b[2 * i], y2 = b[2 * i + 1];
    const double l0 = F.f00 * x1 + F.f01 * y1 + F.f02; // F x1
    const double l1 = F.f10 * x1 + F.f11 * y1 + F.f12;
    const double l2 = F.f20 * x1 + F.f21 * y1 + F.f22;
    const double m0 = F.f00 * x2 + F.f10 * y2 + F.f20; // F^T x2, first two entries
    const double m1 = F.f01 * x2 + F.f11 * y2 + F.f21;
    const double r = x2 * l0 + y2 * l1 + l2;
    rr = r * r;
    jj = l0 * l0 + l1 * l1 + m0 * m0 + m1 * m1;
}

// The points [begin, end) of a set; inlined into each clone of the loops below, so that it is
// compiled for AVX2 and AVX-512 in theirs (geometry/vector_clones.hpp). The loop vectorizes four
// points wide on AVX2: 1.2 ns per point on the project's first machine against 3.3 ns for the SSE2
// baseline and 4.0 ns for the distance-per-point form it replaces; eight wide on AVX-512
// (doc/performance.md, "Large inputs").
template <bool WriteMask>
RCME_ALWAYS_INLINE long long bandBlock(const double* f, const double* a, const double* b,
                                       size_t begin, size_t end, double thresholdSquared,
                                       uchar* mask)
{
    const FundamentalEntries F(f);
    long long count = 0;
    for (size_t i = begin; i < end; ++i) {
        double rr, jj;
        sampsonParts(F, a, b, i, rr, jj);
        // |J| = 0 (a point at an epipole) is never within the band, as its distance is infinite.
        const bool within = (rr <= thresholdSquared * jj) & (jj > 0);
        if (WriteMask)
            mask[i] = within;
        count += within;
    }
    return count;
}

template <bool WriteMask>
RCME_WIDE_VECTOR_CLONES int bandLoop(const double* f, const double* a, const double* b, size_t n,
                                     double thresholdSquared, uchar* mask)
{
    return static_cast<int>(bandBlock<WriteMask>(f, a, b, 0, n, thresholdSquared, mask));
}

// Blocks long enough for the vector loop to run at full speed, short enough that a hypothesis far
// below the needed count stops within a few per cent of a real pair's points.
constexpr size_t kBailOutBlock = 32;

RCME_WIDE_VECTOR_CLONES int bandLoopReaching(const double* f, const double* a, const double* b,
                                             size_t n, double thresholdSquared, long long needed,
                                             size_t& pointsRead)
{
    long long count = 0;
    size_t begin = 0;
    while (begin < n) {
        const size_t end = std::min(n, begin + kBailOutBlock);
        count += bandBlock<false>(f, a, b, begin, end, thresholdSquared, nullptr);
        begin = end;
        if (count + static_cast<long long>(n - end) < needed)
            break;
    }
    pointsRead = begin;
    return static_cast<int>(count);
}

// The truncated cost's points, a chunk at a time: the distances capped into a buffer by a loop of
// bandBlock's shape (which vectorizes), then summed as four partial sums (element j into sum j
// mod 4) added in a fixed order. The vector clone and the baseline one add in the same order, so
// the cost does not depend on the machine; a single running sum would not vectorize.
constexpr size_t kCostChunk = 32;

RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH void
truncatedCostLoop(const double* f, const double* a, const double* b, size_t begin, size_t end,
                  double thresholdSquared, double capSquared, long long& inliers, double& cost)
{
    const FundamentalEntries F(f);
    long long count = 0;
    double capped[kCostChunk];
    while (begin < end) {
        const size_t n = std::min(kCostChunk, end - begin);
        for (size_t i = 0; i < n; ++i) {
            double rr, jj;
            sampsonParts(F, a, b, begin + i, rr, jj);
            count += (rr <= thresholdSquared * jj) & (jj > 0);
            // min(rr / jj, cap) without dividing by a zero |J|: capped wherever rr >= cap jj.
            capped[i] = rr < capSquared * jj ? rr / jj : capSquared;
        }
        for (size_t i = n; i < kCostChunk; ++i)
            capped[i] = 0;
        double sum[4] = {0, 0, 0, 0};
        for (size_t j = 0; j < kCostChunk; j += 4)
            for (size_t k = 0; k < 4; ++k)
                sum[k] += capped[j + k];
        cost += (sum[0] + sum[1]) + (sum[2] + sum[3]);
        begin += n;
    }
    inliers += count;
}

} // namespace

void addTruncatedSampsonCost(const Eigen::Matrix3d& F, const std::vector<Eigen::Vector2d>& points1,
                             const std::vector<Eigen::Vector2d>& points2, size_t begin, size_t end,
                             double thresholdSquared, double capSquared, int& inliers, double& cost)
{
    CV_DbgAssert(points1.size() == points2.size() && end <= points1.size());
    if (begin >= end)
        return;
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> f = F;
    long long count = 0;
    truncatedCostLoop(f.data(), points1.data()->data(), points2.data()->data(), begin, end,
                      thresholdSquared, capSquared, count, cost);
    inliers += static_cast<int>(count);
}

int countInSampsonBand(const Eigen::Matrix3d& F, const Eigen::Vector2d* points1,
                       const Eigen::Vector2d* points2, size_t count, double thresholdSquared,
                       uchar* mask)
{
    if (count == 0)
        return 0;
    // Row-major entries of F; the points are contiguous (x, y) pairs.
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> f = F;
    const double* a = points1->data();
    const double* b = points2->data();
    return mask ? bandLoop<true>(f.data(), a, b, count, thresholdSquared, mask)
                : bandLoop<false>(f.data(), a, b, count, thresholdSquared, nullptr);
}

int countInSampsonBandReaching(const Eigen::Matrix3d& F,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                               int needed, size_t& pointsRead)
{
    CV_DbgAssert(points1.size() == points2.size());
    pointsRead = 0;
    if (points1.empty())
        return 0;
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> f = F;
    return bandLoopReaching(f.data(), points1.data()->data(), points2.data()->data(),
                            points1.size(), thresholdSquared, needed, pointsRead);
}

int countInSampsonBand(const Eigen::Matrix3d& F, const std::vector<Eigen::Vector2d>& points1,
                       const std::vector<Eigen::Vector2d>& points2, double thresholdSquared,
                       uchar* mask)
{
    CV_DbgAssert(points1.size() == points2.size());
    return countInSampsonBand(F, points1.data(), points2.data(), points1.size(), thresholdSquared,
                              mask);
}

} // namespace detail
} // namespace rcme
} // namespace cv
