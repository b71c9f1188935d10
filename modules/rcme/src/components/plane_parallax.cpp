// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Plane and parallax (Hartley & Zisserman, 2nd ed., sec. 13.3; the idea of DEGENSAC, Chum, Werner
// and Matas, CVPR 2005): when a homography H explains most of F's inliers, F = [e']x H, and only
// the correspondences off H's plane tell the epipole e'. Each of them, x2 !~ H x1, puts e' on the
// line through x2 and H x1, so two of them fix it. Without a camera matrix nothing else does, so
// the estimate stands only when the off-plane points that agree with one epipole are more than
// chance alignments: among the m correspondences H does not explain, a random one falls within
// the threshold of a given F with probability p (chanceOfBand), and the best of the epipoles that
// the search tries (pairs of them, and the estimate's) gathers, by chance, at most 2 + the
// Binomial(m - 2, p) quantile at 0.05 / (epipoles tried) (Bonferroni over the epipoles tried). A
// dominant plane with a few points off it keeps its F; a plane with only chance alignments off it
// is degenerate.

#include "components/plane_parallax.hpp"

#include "components/homography_comparison.hpp"
#include "framework/random.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"

#include "opencv2/rcme/opencv_geometry.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Pairs of off-plane points tried: with a fifth of them on the true epipole, 500 pairs hold one
// of its pairs with probability 1 - (1 - 0.04)^500 > 0.99999; fewer off-plane true points are
// not told from chance by the bound anyway.
constexpr int kEpipoleSamples = 500;
constexpr uint64_t kSeed = 0x6a09e667f3bcc909ull;
// How far from H (in inlier thresholds, Sampson distance) a point must be to tell epipoles apart.
constexpr double kOffPlaneThresholds = 3.0;

struct OffPlaneSupport
{
    int agreeing = 0; //!< off-plane points within the threshold of F
    Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
};

// The off-plane correspondences: their indices, and their points side by side for the band's
// vectorized count (countInSampsonBand), which every epipole tried reads.
struct OffPlanePoints
{
    std::vector<int> indices;
    std::vector<Eigen::Vector2d> points1, points2;
};

int countWithin(const TwoViewData& data, const Eigen::Matrix3d& F, const OffPlanePoints& points)
{
    return countInSampsonBand(F, points.points1, points.points2, data.threshold * data.threshold);
}

// The epipole that the most off-plane points agree with, among those of kEpipoleSamples pairs
// (every pair when there are fewer).
OffPlaneSupport bestEpipole(const TwoViewData& data, const Eigen::Matrix3d& H,
                            const OffPlanePoints& offPlanePoints)
{
    const std::vector<int>& offPlane = offPlanePoints.indices;
    OffPlaneSupport best;
    const size_t m = offPlane.size();
    const long long pairs = static_cast<long long>(m) * static_cast<long long>(m - 1) / 2;
    const bool everyPair = pairs <= kEpipoleSamples;
    uint64_t state = kSeed;
    size_t a = 0, b = 1;
    for (int s = 0; s < (everyPair ? static_cast<int>(pairs) : kEpipoleSamples); ++s) {
        if (everyPair) {
            if (s > 0 && ++b == m) {
                ++a;
                b = a + 1;
            }
        } else {
            a = uniformBelow(state, static_cast<uint32_t>(m));
            do
                b = uniformBelow(state, static_cast<uint32_t>(m));
            while (b == a);
        }
        const size_t i = static_cast<size_t>(offPlane[a]), j = static_cast<size_t>(offPlane[b]);
        const Eigen::Vector3d lineI =
            homogeneous(data.points2[i]).cross(H * homogeneous(data.points1[i]));
        const Eigen::Vector3d lineJ =
            homogeneous(data.points2[j]).cross(H * homogeneous(data.points1[j]));
        const Eigen::Vector3d epipole = lineI.cross(lineJ);
        Eigen::Matrix3d F = skew(epipole) * H;
        const double norm = F.norm();
        if (!(norm > 0) || !F.allFinite())
            continue;
        F /= norm;
        const int agreeing = countWithin(data, F, offPlanePoints);
        if (agreeing > best.agreeing) {
            best.agreeing = agreeing;
            best.F = F;
        }
    }
    return best;
}

} // namespace

StageOutcome resolvePlaneAndParallax(const TwoViewData& data, Scorer& scorer,
                                     const Eigen::Matrix3d& H, const Estimate& estimate)
{
    // Off the plane: farther from H than kOffPlaneThresholds thresholds. A point nearer H lies
    // within the threshold of most F of the family [e']x H, whatever e', and would count for
    // every epipole.
    const double offPlaneCut =
        kOffPlaneThresholds * kOffPlaneThresholds * data.threshold * data.threshold;
    OffPlanePoints offPlane;
    for (size_t i = 0; i < data.points1.size(); ++i)
        if (!(homographySampsonSquared(H, data.points1[i], data.points2[i]) <= offPlaneCut)) {
            offPlane.indices.push_back(static_cast<int>(i));
            offPlane.points1.push_back(data.points1[i]);
            offPlane.points2.push_back(data.points2[i]);
        }
    const int m = static_cast<int>(offPlane.indices.size());
    // Bonferroni over the epipoles the search tries, not over every pair, which it does not try
    // beyond kEpipoleSamples: with 150-165 off-plane points the bound is 12-13 agreeing points
    // instead of 14-15, which 20 true points a few pixels off the plane reach (doc/f_only.md,
    // "The chance bound counts the epipoles tried").
    const double tried = std::min(0.5 * m * (m - 1.0), static_cast<double>(kEpipoleSamples)) + 1.0;
    const int chance =
        m < 2 ? 2 : 2 + binomialTailBound(m - 2, chanceOfBand(data, data.threshold), 0.05 / tried);
    const int estimateAgreeing = countWithin(data, estimate.model.F, offPlane);
    OffPlaneSupport best = m < 2 ? OffPlaneSupport() : bestEpipole(data, H, offPlane);
    if (estimateAgreeing >= best.agreeing) {
        best.agreeing = estimateAgreeing;
        best.F = estimate.model.F;
    }
    if (best.agreeing <= chance)
        return StageOutcome::rejecting(
            STATUS_DEGENERATE_CONFIGURATION,
            cv::format("a homography explains the inliers as well as F, and of the %d "
                       "correspondences off its plane at most %d agree with one epipole, no more "
                       "than chance alignments (up to %d): F is not determined without the camera "
                       "matrix",
                       m, best.agreeing, chance),
            estimate.model);
    if (best.agreeing == estimateAgreeing)
        return {};
    Fit parallax{estimate.model, Score(), {}};
    parallax.model.F = best.F;
    parallax.model.uncertainty.reset();
    scorer.classify(data, parallax.model, parallax.inliers);
    parallax.score = scorer.score(data, parallax.model);
    return StageOutcome::revised(std::move(parallax));
}

} // namespace detail
} // namespace rcme
} // namespace cv
