// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

bool similarityOf(const Eigen::Vector2d& centroid, double meanDistance, Eigen::Matrix3d& T)
{
    if (!(meanDistance > 1e-9 * (1.0 + centroid.norm())))
        return false;
    const double scale = std::sqrt(2.0) / meanDistance;
    T << scale, 0, -scale * centroid.x(), 0, scale, -scale * centroid.y(), 0, 0, 1;
    return true;
}

} // namespace

bool normalizingTransforms(const std::vector<Eigen::Vector2d>& points1,
                           const std::vector<Eigen::Vector2d>& points2,
                           const std::vector<int>& indices, Eigen::Matrix3d& T1,
                           Eigen::Matrix3d& T2)
{
    // The two images' sums side by side, each in the indices' order: each addition waits for the
    // previous one of its own sum only, so a large set takes about half the time of one image
    // after the other, with the same sums.
    Eigen::Vector2d centroid1 = Eigen::Vector2d::Zero(), centroid2 = Eigen::Vector2d::Zero();
    for (int i : indices) {
        centroid1 += points1[static_cast<size_t>(i)];
        centroid2 += points2[static_cast<size_t>(i)];
    }
    const double count = static_cast<double>(indices.size());
    centroid1 /= count;
    centroid2 /= count;
    double meanDistance1 = 0, meanDistance2 = 0;
    for (int i : indices) {
        meanDistance1 += (points1[static_cast<size_t>(i)] - centroid1).norm();
        meanDistance2 += (points2[static_cast<size_t>(i)] - centroid2).norm();
    }
    meanDistance1 /= count;
    meanDistance2 /= count;
    return similarityOf(centroid1, meanDistance1, T1) && similarityOf(centroid2, meanDistance2, T2);
}

Eigen::Matrix3d normalizeFundamental(const Eigen::Matrix3d& F)
{
    const double norm = F.norm();
    if (!(norm > 0))
        return F;
    Eigen::Index row = 0, col = 0;
    F.cwiseAbs().maxCoeff(&row, &col);
    return (F(row, col) < 0 ? -1.0 : 1.0) / norm * F;
}

Eigen::Matrix3d closestRankTwo(const Eigen::Matrix3d& F)
{
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(F.transpose() * F);
    const Eigen::Vector3d v = eig.eigenvectors().col(0); // eigenvalues in increasing order
    return F - (F * v) * v.transpose();
}

Eigen::Matrix3d projectToEssential(const Eigen::Matrix3d& E)
{
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
    return svd.matrixU() * Eigen::Vector3d(1, 1, 0).asDiagonal() * svd.matrixV().transpose();
}

Eigen::Matrix3d essentialFromFundamental(const Eigen::Matrix3d& F, const Eigen::Matrix3d& K)
{
    return projectToEssential(K.transpose() * F * K);
}

Eigen::Matrix3d fundamentalFromEssential(const Eigen::Matrix3d& E, const Eigen::Matrix3d& Kinv)
{
    return normalizeFundamental(Kinv.transpose() * E * Kinv);
}

namespace {

// Depths (in camera 1 and camera 2) of the point seen along rays y1, y2 under x2 = R x1 + t,
// by least squares on lambda2 y2 = lambda1 R y1 + t. False for (near) parallel rays.
bool triangulateDepths(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                       const Eigen::Vector3d& y1, const Eigen::Vector3d& y2, double& depth1,
                       double& depth2)
{
    const Eigen::Vector3d a = R * y1;
    // Solve [a, -y2] [l1; l2] = -t in the least-squares sense.
    const double aa = a.dot(a), ab = -a.dot(y2), bb = y2.dot(y2);
    const double det = aa * bb - ab * ab;
    if (!(det > 1e-12 * aa * bb))
        return false;
    const double ra = -a.dot(t), rb = y2.dot(t);
    const double l1 = (bb * ra - ab * rb) / det;
    depth1 = l1 * y1.z();
    depth2 = (R * (l1 * y1) + t).z();
    return true;
}

} // namespace

bool admitsCommonCheirality(const Eigen::Matrix3d& E, const Eigen::Vector3d* q1,
                            const Eigen::Vector3d* q2, int count)
{
    // t^T E = 0: the largest cross product of two columns of E.
    Eigen::Vector3d t = E.col(0).cross(E.col(1));
    for (const Eigen::Vector3d& other :
         {Eigen::Vector3d(E.col(0).cross(E.col(2))), Eigen::Vector3d(E.col(1).cross(E.col(2)))})
        if (other.squaredNorm() > t.squaredNorm())
            t = other;
    int positive = 0, negative = 0;
    for (int k = 0; k < count; ++k) {
        const double s = t.cross(q2[k]).dot(E * q1[k]);
        positive += s > 0;
        negative += s < 0;
    }
    return positive == 0 || negative == 0;
}

int countPointsInFront(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                       const std::vector<Eigen::Vector2d>& points1,
                       const std::vector<Eigen::Vector2d>& points2, const Eigen::Matrix3d& Kinv,
                       const std::vector<uchar>* selection, std::vector<uchar>* inFront,
                       double distanceThreshold)
{
    const size_t n = points1.size();
    if (inFront)
        inFront->assign(n, 0);
    int count = 0;
    for (size_t i = 0; i < n; ++i) {
        if (selection && !(*selection)[i])
            continue;
        double d1 = 0, d2 = 0;
        if (triangulateDepths(R, t, Kinv * homogeneous(points1[i]), Kinv * homogeneous(points2[i]),
                              d1, d2) &&
            d1 > 0 && d2 > 0 && d1 < distanceThreshold && d2 < distanceThreshold) {
            ++count;
            if (inFront)
                (*inFront)[i] = 1;
        }
    }
    return count;
}

int recoverMotionFromEssential(const Eigen::Matrix3d& E,
                               const std::vector<Eigen::Vector2d>& points1,
                               const std::vector<Eigen::Vector2d>& points2,
                               const Eigen::Matrix3d& Kinv, const std::vector<uchar>* selection,
                               Eigen::Matrix3d& R, Eigen::Vector3d& t, double distanceThreshold)
{
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU(), V = svd.matrixV();
    if (U.determinant() < 0)
        U = -U;
    if (V.determinant() < 0)
        V = -V;
    Eigen::Matrix3d W;
    W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    const Eigen::Matrix3d rotations[2] = {U * W * V.transpose(), U * W.transpose() * V.transpose()};
    const Eigen::Vector3d direction = U.col(2).normalized();
    // The four candidates (R_k, +-direction) counted in one pass, each point's rays computed once.
    // triangulateDepths is linear in t and negating is exact, so the depths under -direction are
    // those under +direction negated, bit for bit: countPointsInFront of each candidate.
    int counts[4] = {0, 0, 0, 0};
    const auto inFront = [distanceThreshold](double d1, double d2) {
        return d1 > 0 && d2 > 0 && d1 < distanceThreshold && d2 < distanceThreshold;
    };
    for (size_t i = 0; i < points1.size(); ++i) {
        if (selection && !(*selection)[i])
            continue;
        const Eigen::Vector3d y1 = Kinv * homogeneous(points1[i]);
        const Eigen::Vector3d y2 = Kinv * homogeneous(points2[i]);
        for (int k = 0; k < 2; ++k) {
            double d1 = 0, d2 = 0;
            if (!triangulateDepths(rotations[k], direction, y1, y2, d1, d2))
                continue;
            counts[2 * k] += inFront(d1, d2);
            counts[2 * k + 1] += inFront(-d1, -d2);
        }
    }
    int bestCount = -1;
    for (int candidate = 0; candidate < 4; ++candidate) {
        if (counts[candidate] > bestCount) {
            bestCount = counts[candidate];
            R = rotations[candidate / 2];
            t = (candidate % 2 == 0) ? direction : Eigen::Vector3d(-direction);
        }
    }
    return bestCount;
}

} // namespace detail
} // namespace rcme
} // namespace cv
