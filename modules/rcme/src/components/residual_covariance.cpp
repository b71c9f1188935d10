// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The reported covariance (Params::useEstimatedNoise, with a camera matrix). Its noise: the final
// fit scaled its covariance sigma^2 / h (J^T J)^-1 with the noise estimated from the inliers'
// residuals from 30 residual degrees of freedom on and with the stated sigma below (the
// uncertainty bound decides on that covariance, its bounds were chosen with it); a pair just
// below 35 inliers took a variance about ten times its neighbour's on real matches. The reported
// one uses the posterior noise at every count instead: the estimate shrunk toward the stated sigma
// with a weight that grows with the residual degrees of freedom (posteriorNoiseVariance). Its
// shape: one noise for every inlier is over-confident where the points that determine a direction
// of the motion are the noisier ones, as real matches' noise differs from point to point; the
// residual-based (sandwich) covariance A^-1 S A^-1 n / (n - 5) / h^2, A = J^T J,
// S = sum d_i^2 / (1 - h_i)^2 g_i^T g_i (h_i the inlier's leverage), sees that, and from 30
// residual degrees of freedom on the reported covariance is raised to it along the directions where
// it exceeds the model-based one by more than its own sampling noise. Outliers that fall into the
// band are inliers to every term above; their number is read off the points just outside the band,
// and the excess variance of those hidden within the noise's own band is added. A motion the final
// polish refitted with its Cauchy loss is that M-estimator's: its own sandwich replaces least
// squares', and it may lower the model-based form as well as raise it. Measured on real pairs and
// synthetic scenes in doc/covariance.md.

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "geometry/covariance_combination.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

constexpr int P = MotionTangent::kDof;
using Matrix = Eigen::Matrix<double, P, P>;

/* The stated sigma's weight as a prior on the noise, in residual degrees of freedom: picked among
0-30 on templeSR's ground truth and KITTI 06's loops at two shares of the matches
(doc/covariance.md): the stated sigma weighs 4 / (4 + dof) of the posterior, 12 % at 35 inliers, 2 %
at 200. */
constexpr double kStatedNoiseDof = 4.0;

/* A point's residual at a fit it took part in is shrunk by its leverage h (d = (1 - h) e to first
order), so the plain sandwich sum d^2 g^T g misses most of what a point of high leverage adds to
the motion's error: each inlier's term is divided by (1 - h)^2 (the jackknife's form, HC3 in
MacKinnon and White's naming). An outlier that the fitted motion lets into the band has a leverage
a dozen times an inlier's (median 0.085 against 0.006 on the synthetic scenes with 30 % outliers,
doc/covariance.md). Leverages above 0.99 (one point alone fixes a direction, its residual is
roundoff) are taken as 0.99. */
constexpr double kMinLeverageComplement = 0.01;

/* Outliers fall into the band too. Random matches' Sampson distances have a flat density near the
epipolar line, so the points outside the band with distances between kNearFrom and kNearTo band
widths c say how many outliers the band holds: 1 / (kNearTo - kNearFrom) of them. From 2c = 3.9
sigma on, the inliers' own tail is below 1e-4 of them. */
constexpr double kNearFrom = 2.0, kNearTo = 6.0;

// What the returned motion's inliers and the points just outside its band say about its error.
struct ResidualScores
{
    Matrix informationInverse; //!< (J^T J)^-1 over the inliers
    Matrix scatter;            //!< sum d_i^2 / (1 - h_i)^2 g_i^T g_i over the inliers
    Matrix nearOutliers;       //!< sum g^T g over the points between kNearFrom c and kNearTo c
    //! With a polished motion (Model::polishLossScale s), its Cauchy loss's M-estimator terms:
    //! sum psi'(d_i) g_i^T g_i and sum psi(d_i)^2 / (1 - h_i)^2 g_i^T g_i, psi(d) = d / (1 + d^2 /
    //! s^2); and the loss's variance factor against least squares over the same residuals.
    Matrix robustCurvature, robustScatter;
    double robustFactor = 1.0; //!< CauchyVarianceFactor, NaN where it does not apply
};

// The scores over the mask's points and the points near its band, at the motion the directions
// were taken at; none when J^T J is singular.
bool residualScores(const TwoViewData& data, const Model& model, const std::vector<uchar>& mask,
                    int count, ResidualScores& scores)
{
    // The Sampson distances' gradients (F in the scale of its derivatives, not Model::F).
    const Eigen::Matrix3d F =
        data.Kinv.transpose() * skew(model.motion()->t) * model.motion()->R * data.Kinv;
    const double nearFrom = kNearFrom * kNearFrom * data.threshold * data.threshold,
                 nearTo = kNearTo * kNearTo * data.threshold * data.threshold;
    std::vector<Eigen::Matrix<double, 1, P>> gradients;
    std::vector<double> distances;
    gradients.reserve(count);
    distances.reserve(count);
    const Eigen::Matrix3d* directions = model.uncertainty.as<MotionUncertainty>()->directions;
    Matrix information = Matrix::Zero();
    scores.nearOutliers.setZero();
    Eigen::Matrix<double, 1, P> g;
    double d = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) {
            const double squared = sampsonDistanceSquared(F, data.points1[i], data.points2[i]);
            if (squared > nearFrom && squared <= nearTo &&
                sampsonDistanceAndGradient<P>(F, directions, data.points1[i], data.points2[i], d,
                                              g))
                scores.nearOutliers.noalias() += g.transpose() * g;
            continue;
        }
        if (!sampsonDistanceAndGradient<P>(F, directions, data.points1[i], data.points2[i], d, g))
            continue;
        information.noalias() += g.transpose() * g;
        gradients.push_back(g);
        distances.push_back(d);
    }
    const Eigen::LDLT<Matrix> ldlt(information);
    if (ldlt.info() != Eigen::Success)
        return false;
    scores.informationInverse = ldlt.solve(Matrix::Identity());
    scores.scatter.setZero();
    scores.robustCurvature.setZero();
    scores.robustScatter.setZero();
    const double s2 = model.polishLossScale * model.polishLossScale;
    CauchyVarianceFactor factor(s2);
    for (size_t i = 0; i < gradients.size(); ++i) {
        const double leverage = gradients[i] * scores.informationInverse * gradients[i].transpose();
        const double shrink = std::max(1.0 - leverage, kMinLeverageComplement);
        const Matrix outer = gradients[i].transpose() * gradients[i];
        const double d2 = distances[i] * distances[i];
        scores.scatter.noalias() += (d2 / (shrink * shrink)) * outer;
        if (s2 > 0) {
            const double w = 1.0 / (1.0 + d2 / s2);
            scores.robustCurvature.noalias() += ((1.0 - d2 / s2) * w * w) * outer;
            scores.robustScatter.noalias() += (d2 * w * w / (shrink * shrink)) * outer;
            factor.add(d2);
        }
    }
    scores.robustFactor = s2 > 0 ? factor.value() : 1.0;
    return true;
}

class ResidualCovariance final : public EstimationStage
{
public:
    StageOutcome run(const StageContext& context, const Estimate& estimate) override
    {
        const TwoViewData& data = context.data;
        const Model& model = estimate.model;
        const int count = static_cast<int>(
            std::count(estimate.mask.begin(), estimate.mask.end(), static_cast<uchar>(1)));
        const int dof = count - P;
        const MotionUncertainty* uncertainty = model.uncertainty.as<MotionUncertainty>();
        if (!uncertainty || !model.motion() || !data.useEstimatedNoise || dof < 1 ||
            !std::isfinite(model.noiseSigma))
            return {};
        const bool estimated = usesEstimatedNoise(data, model.noiseSigma, dof);
        const double fitted = estimated ? model.noiseSigma : data.sigma;
        const double posterior =
            posteriorNoiseVariance(data.sigma, model.noiseSigma, dof, kStatedNoiseDof);
        const Matrix modelBased =
            uncertainty->covariance * (truncatedNoiseVariance(posterior, data.threshold) /
                                       truncatedNoiseVariance(fitted * fitted, data.threshold));
        StageOutcome outcome;
        Model& revised = outcome.model.emplace(model);
        Matrix covariance = modelBased;
        ResidualScores scores;
        if (residualScores(data, model, estimate.mask, count, scores)) {
            // The sandwich A^-1 S A^-1 n / (n - 5) / h^2 in the fitted noise's truncation h.
            const double h = truncatedNormalVariance(data.threshold / fitted);
            const double n = static_cast<double>(count);
            const Eigen::LDLT<Matrix> robust(scores.robustCurvature);
            const bool polished = model.polishLossScale > 0 && scores.robustFactor < 1.0 &&
                                  robust.info() == Eigen::Success && robust.isPositive();
            if (estimated && polished) {
                // A polished motion is the loss's M-estimate: its own sandwich, beside the
                // model-based covariance scaled by the loss's variance factor. That factor takes
                // one noise for every inlier, so here the sandwich lowers the model-based form too
                // where it is smaller beyond its noise: raising alone stays conservative on real
                // loops, and the sandwich alone is over-confident on small sets
                // (doc/covariance.md).
                const Matrix curvatureInverse = robust.solve(Matrix::Identity());
                covariance =
                    sandwichBeyondItsNoise<P>(modelBased * scores.robustFactor,
                                              curvatureInverse * scores.robustScatter *
                                                  curvatureInverse * (n / (n - P) / (h * h)),
                                              n, /*lowerToo=*/true);
            } else if (estimated)
                covariance = sandwichBeyondItsNoise<P>(modelBased,
                                                       scores.informationInverse * scores.scatter *
                                                           scores.informationInverse *
                                                           (n / (n - P) / (h * h)),
                                                       n, /*lowerToo=*/false);
            // The outliers in the band that the residuals cannot show: those within the noise's
            // own 95 % band w = min(c, 1.96 sigma), a share w / c of the band's, their residuals
            // spread over it (variance w^2 / 3) where the terms above count them as inliers; one
            // beyond w stands out of the inliers' residuals and the sandwich weighs it by its own.
            // Their gradients: the points near the band's. sigma: the reported covariance's noise.
            static const double noiseBand = normalQuantile(0.975);
            const double sigma = std::sqrt(posterior);
            const double w = std::min(data.threshold, noiseBand * sigma);
            const double excess =
                w / data.threshold *
                std::max(0.0, w * w / 3.0 - truncatedNormalVariance(w / sigma) * posterior);
            const double hReported = truncatedNormalVariance(data.threshold / sigma);
            covariance += scores.informationInverse * scores.nearOutliers *
                          scores.informationInverse *
                          (excess / (kNearTo - kNearFrom) / (hReported * hReported));
        }
        revised.uncertainty.as<MotionUncertainty>()->covariance = covariance;
        return outcome;
    }
};

} // namespace

std::unique_ptr<EstimationStage> createResidualCovariance()
{
    return std::make_unique<ResidualCovariance>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
