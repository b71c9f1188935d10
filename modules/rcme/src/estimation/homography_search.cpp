// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "estimation/homography_search.hpp"

#include "framework/random.hpp"
#include "geometry/statistics.hpp"
#include "geometry/vector_clones.hpp"

#include <algorithm>
#include <cmath>

namespace cv {
namespace rcme {
namespace detail {

namespace {

/* Whether the four points of `sample` are ordered alike (every triangle of them with the same
orientation) in both images. A homography of a plane seen from one side of it by both cameras
keeps that order; a sample that breaks it gives a twisted homography of no plane, which can still
hold a few chance points among few candidates. (OpenCV's findHomography refuses such samples
too.) */
bool keepsOrientation(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                      const int sample[4])
{
    const auto orientation = [](const std::vector<Point2d>& p, int a, int b, int c) {
        const Point2d u = p[static_cast<size_t>(b)] - p[static_cast<size_t>(a)];
        const Point2d v = p[static_cast<size_t>(c)] - p[static_cast<size_t>(a)];
        return u.x * v.y - u.y * v.x;
    };
    constexpr int kTriangles[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    for (const auto& t : kTriangles) {
        const double before = orientation(from, sample[t[0]], sample[t[1]], sample[t[2]]);
        const double after = orientation(to, sample[t[0]], sample[t[1]], sample[t[2]]);
        if (before * after < 0)
            return false;
    }
    return true;
}

// The row-major entries of H and the points as (x, y) pairs; each lane's arithmetic is one
// point's, in the order of the expression below, on every clone.
RCME_VECTOR_CLONES RCME_SPECULATIVE_MATH int transferredLoop(const double* h, const double* a,
                                                             const double* b, size_t begin,
                                                             size_t end, double threshold2,
                                                             uchar* held)
{
    const double h00 = h[0], h01 = h[1], h02 = h[2], h10 = h[3], h11 = h[4], h12 = h[5], h20 = h[6],
                 h21 = h[7], h22 = h[8];
    int count = 0;
    for (size_t i = begin; i < end; ++i) {
        const double x = a[2 * i], y = a[2 * i + 1];
        const double u = h00 * x + h01 * y + h02;
        const double v = h10 * x + h11 * y + h12;
        const double w = h20 * x + h21 * y + h22;
        const double dx = u / w - b[2 * i], dy = v / w - b[2 * i + 1];
        const bool within = dx * dx + dy * dy <= threshold2;
        held[i - begin] = within;
        count += within;
    }
    return count;
}

// The points of `to` within squared transfer distance `threshold2` of H applied to `from`.
void transferInliers(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                     const Eigen::Matrix3d& H, double threshold2, std::vector<int>& inliers)
{
    inliers.clear();
    uchar held[kTransferBlock];
    for (size_t begin = 0; begin < from.size(); begin += kTransferBlock) {
        const size_t end = std::min(from.size(), begin + kTransferBlock);
        markTransferredWithin(H, from, to, begin, end, threshold2, held);
        for (size_t i = begin; i < end; ++i)
            if (held[i - begin])
                inliers.push_back(static_cast<int>(i));
    }
}

/* Least squares (the direct linear transform) on the correspondences `indices`: the unit vector h
minimizing |A h| over their two equations each. False when they do not determine H. */
bool homographyOfMany(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                      const std::vector<int>& indices, Eigen::Matrix3d& H)
{
    if (indices.size() < 4)
        return false;
    // The lower triangle of sum a a^T + b b^T, written out: Eigen's rank-one update of a fixed
    // 9 x 9 matrix goes through its general product kernel, several times slower here.
    Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
    for (int i : indices) {
        const Point2d& p = from[static_cast<size_t>(i)];
        const Point2d& q = to[static_cast<size_t>(i)];
        const double a[9] = {p.x, p.y, 1, 0, 0, 0, -q.x * p.x, -q.x * p.y, -q.x};
        const double b[9] = {0, 0, 0, p.x, p.y, 1, -q.y * p.x, -q.y * p.y, -q.y};
        for (int c = 0; c < 9; ++c)
            for (int r = c; r < 9; ++r)
                AtA(r, c) += a[r] * a[c];
        for (int c = 0; c < 9; ++c)
            for (int r = c; r < 9; ++r)
                AtA(r, c) += b[r] * b[c];
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(
        AtA.selfadjointView<Eigen::Lower>());
    if (eigen.info() != Eigen::Success || !(eigen.eigenvalues()(1) > 0))
        return false;
    const Eigen::Matrix<double, 9, 1> h = eigen.eigenvectors().col(0);
    H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
    return H.allFinite();
}

} // namespace

int markTransferredWithin(const Eigen::Matrix3d& H, const std::vector<Point2d>& from,
                          const std::vector<Point2d>& to, size_t begin, size_t end,
                          double threshold2, uchar* held)
{
    CV_DbgAssert(from.size() == to.size() && begin <= end && end <= from.size());
    if (begin >= end)
        return 0;
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> h = H;
    return transferredLoop(h.data(), &from[0].x, &to[0].x, begin, end, threshold2, held);
}

int transferredUnlessBeaten(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                            const Eigen::Matrix3d& H, double threshold2, int toBeat)
{
    // Stops a block at a time: once the points left cannot lift the count above toBeat, none
    // that follow can either.
    const size_t count = from.size();
    uchar held[kTransferBlock];
    int total = 0;
    for (size_t begin = 0; begin < count && total + static_cast<long long>(count - begin) > toBeat;
         begin += kTransferBlock)
        total += markTransferredWithin(H, from, to, begin, std::min(count, begin + kTransferBlock),
                                       threshold2, held);
    return total;
}

Normalization normalizeInPlace(std::vector<Point2d>& points)
{
    Normalization n;
    for (const Point2d& p : points)
        n.centre += p;
    n.centre *= 1.0 / static_cast<double>(points.size());
    double distance = 0;
    for (const Point2d& p : points)
        distance += cv::norm(p - n.centre);
    n.scale = distance > 0 ? std::sqrt(2.0) * points.size() / distance : 1.0;
    for (Point2d& p : points)
        p = (p - n.centre) * n.scale;
    return n;
}

namespace {

/* The projective basis of four points: B with B e_k ~ p_k (k < 3) and B (1, 1, 1) ~ p_4, that is
B = [p_1 p_2 p_3] diag(lambda) with [p_1 p_2 p_3] lambda = p_4 (homogeneous points). False when
three of the four lie on a line (a vanishing determinant, relative to Hadamard's bound). */
bool projectiveBasis(const std::vector<Point2d>& points, const int sample[4], Eigen::Matrix3d& M,
                     Eigen::Vector3d& lambda)
{
    for (int k = 0; k < 3; ++k) {
        const Point2d& p = points[static_cast<size_t>(sample[k])];
        M.col(k) << p.x, p.y, 1.0;
    }
    const Point2d& q = points[static_cast<size_t>(sample[3])];
    const Eigen::Vector3d p4(q.x, q.y, 1.0);
    // Cramer's rule: lambda_k det M is the determinant with column k replaced by p4.
    const Eigen::Vector3d c01 = M.col(0).cross(M.col(1)), c12 = M.col(1).cross(M.col(2)),
                          c20 = M.col(2).cross(M.col(0));
    const double det = c01.dot(M.col(2));
    const double n0 = M.col(0).norm(), n1 = M.col(1).norm(), n2 = M.col(2).norm(), n4 = p4.norm();
    constexpr double kCollinear = 1e-10;
    const Eigen::Vector3d scaled(c12.dot(p4), c20.dot(p4), c01.dot(p4));
    if (!(std::abs(det) > kCollinear * n0 * n1 * n2) ||
        !(std::abs(scaled(0)) > kCollinear * n4 * n1 * n2) ||
        !(std::abs(scaled(1)) > kCollinear * n0 * n4 * n2) ||
        !(std::abs(scaled(2)) > kCollinear * n0 * n1 * n4))
        return false;
    lambda = scaled / det;
    return true;
}

} // namespace

bool homographyOfFour(const std::vector<Point2d>& from, const std::vector<Point2d>& to,
                      const int sample[4], Eigen::Matrix3d& H)
{
    // H = B_to B_from^-1, both bases of the sample (Hartley & Zisserman, 2nd ed., ex. 4.1):
    // closed form, a fraction of solving the eight equations.
    Eigen::Matrix3d M1, M2;
    Eigen::Vector3d lambda1, lambda2;
    if (!projectiveBasis(from, sample, M1, lambda1) || !projectiveBasis(to, sample, M2, lambda2))
        return false;
    Eigen::Matrix3d adjugate1; // adj(M1) = det(M1) M1^-1: rows are cross products of columns
    adjugate1.row(0) = M1.col(1).cross(M1.col(2)).transpose();
    adjugate1.row(1) = M1.col(2).cross(M1.col(0)).transpose();
    adjugate1.row(2) = M1.col(0).cross(M1.col(1)).transpose();
    H = M2 * lambda2.cwiseQuotient(lambda1).asDiagonal() * adjugate1;
    if (!(std::abs(H(2, 2)) > 1e-12 * H.norm()))
        return false;
    H /= H(2, 2);
    return H.allFinite();
}

// At most 200 samples: H can only win the comparison when it holds most of the candidates (F's
// per-point penalty is log 4), and then 200 samples find it with certainty (50 lost a winning H of
// 126 of 258 matches on KITTI-01 16-21, whose planar path returns the right motion). A large set
// is searched on an evenly spaced subset (kMaxIteratedPoints): twenty thousand points decide
// whether a homography explains them; the comparison takes every candidate.
bool dominantHomography(const std::vector<Point2d>& candidates1,
                        const std::vector<Point2d>& candidates2, double transferThreshold,
                        Eigen::Matrix3d& H)
{
    constexpr int kMaxSamples = 200, kMaxRefits = 5;
    constexpr double kConfidence = 0.999;
    if (candidates1.size() < 4 || candidates1.size() != candidates2.size())
        return false;
    const size_t stride = subsetStride(candidates1.size());
    std::vector<Point2d> points1, points2;
    for (size_t i = 0; i < candidates1.size(); i += stride) {
        points1.push_back(candidates1[i]);
        points2.push_back(candidates2[i]);
    }
    const Normalization n1 = normalizeInPlace(points1), n2 = normalizeInPlace(points2);
    const double threshold2 = transferThreshold * transferThreshold * n2.scale * n2.scale;
    const uint32_t count = static_cast<uint32_t>(points1.size());

    Eigen::Matrix3d best = Eigen::Matrix3d::Zero();
    int bestHeld = 0;
    double samplesNeeded = kMaxSamples;
    uint64_t state = 0x243f6a8885a308d3ull; // fixed: the test is reproducible
    std::vector<int> drawn(4);
    int sample[4];
    for (int s = 0; s < kMaxSamples && s < samplesNeeded; ++s) {
        drawDistinct(state, count, 0, drawn);
        std::copy(drawn.begin(), drawn.end(), sample);
        Eigen::Matrix3d candidate;
        if (!keepsOrientation(points1, points2, sample) ||
            !homographyOfFour(points1, points2, sample, candidate))
            continue;
        const int held = transferredUnlessBeaten(points1, points2, candidate, threshold2, bestHeld);
        if (held > bestHeld) {
            bestHeld = held;
            best = candidate;
            const double share = static_cast<double>(held) / count;
            samplesNeeded = samplesForConfidence(kConfidence, share * share * share * share);
        }
    }
    if (bestHeld < 4)
        return false;
    std::vector<int> held, refitHeld;
    transferInliers(points1, points2, best, threshold2, held);
    for (int refit = 0; refit < kMaxRefits; ++refit) {
        Eigen::Matrix3d refitted;
        if (!homographyOfMany(points1, points2, held, refitted))
            break;
        transferInliers(points1, points2, refitted, threshold2, refitHeld);
        if (refitHeld.size() < held.size())
            break;
        best = refitted;
        const bool settled = refitHeld == held;
        held.swap(refitHeld);
        if (settled)
            break;
    }
    H = n2.matrix().inverse() * best * n1.matrix();
    if (!(std::abs(H(2, 2)) > 0) || !H.allFinite())
        return false;
    H /= H(2, 2);
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
