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
// S = sum d_i^2 g_i^T g_i, sees that, and from 30 residual degrees of freedom on the reported
// covariance is raised to it along the directions where it exceeds the model-based one by more
// than its own sampling noise. Measured on real pairs and synthetic scenes in doc/covariance.md.

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

constexpr int P = MotionTangent::kDof;
using Matrix = Eigen::Matrix<double, P, P>;

/* In the coordinates where the model-based covariance is the identity (C = L L^T), the sandwich's
eigenvalues are lowered by two of their standard errors under Gaussian noise, about sqrt(2 / n)
each (a mean of n squared residuals), and those below 1 raised to 1: the smallest covariance that
is at least both along every direction once the sandwich's sampling noise is discounted. Without
the margin, the larger of two noisy estimates makes a calibrated covariance conservative on
synthetic scenes (rotation NEES mean 2.50 instead of 2.68; with it 2.62, doc/covariance.md). */
Matrix raisedToSandwich(const Matrix& modelBased, const Matrix& sandwich, double count)
{
    const Eigen::LLT<Matrix> factor(modelBased);
    if (factor.info() != Eigen::Success || !sandwich.allFinite())
        return modelBased;
    const Matrix L = factor.matrixL();
    Matrix whitened = factor.matrixL().solve(sandwich);
    whitened = factor.matrixL().solve(whitened.transpose()).transpose();
    const Eigen::SelfAdjointEigenSolver<Matrix> eig(0.5 * (whitened + whitened.transpose()));
    const double margin = 2.0 * std::sqrt(2.0 / count);
    const Matrix raised = eig.eigenvectors() *
                          (eig.eigenvalues().array() - margin).max(1.0).matrix().asDiagonal() *
                          eig.eigenvectors().transpose();
    return L * raised * L.transpose();
}

/* The stated sigma's weight as a prior on the noise, in residual degrees of freedom: picked among
0-30 on templeSR's ground truth and KITTI 06's loops at two shares of the matches
(doc/covariance.md): the stated sigma weighs 4 / (4 + dof) of the posterior, 12 % at 35 inliers, 2 %
at 200. */
constexpr double kStatedNoiseDof = 4.0;

// A^-1 S A^-1 n / (n - 5) / h^2 over the mask's points, at the motion the directions were taken
// at; none when A is singular.
bool sandwichCovariance(const TwoViewData& data, const Model& model, const std::vector<uchar>& mask,
                        int count, Matrix& sandwich)
{
    // The Sampson distances' gradients (F in the scale of its derivatives, not Model::F).
    const Eigen::Matrix3d F =
        data.Kinv.transpose() * skew(model.motion->t) * model.motion->R * data.Kinv;
    Matrix information = Matrix::Zero(), scatter = Matrix::Zero();
    const Eigen::Matrix3d* directions = model.uncertainty.as<MotionUncertainty>()->directions;
    Eigen::Matrix<double, 1, P> g;
    double d = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i] ||
            !sampsonDistanceAndGradient<P>(F, directions, data.points1[i], data.points2[i], d, g))
            continue;
        information.noalias() += g.transpose() * g;
        scatter.noalias() += (d * d) * (g.transpose() * g);
    }
    const Eigen::LDLT<Matrix> ldlt(information);
    if (ldlt.info() != Eigen::Success)
        return false;
    const Matrix informationInverse = ldlt.solve(Matrix::Identity());
    const double h = truncatedNormalVariance(data.threshold / model.noiseSigma);
    const double n = static_cast<double>(count);
    sandwich = informationInverse * scatter * informationInverse * (n / (n - P) / (h * h));
    return true;
}

// sigma^2 / h(c / sigma), the model-based covariance's factor on (J^T J)^-1.
double truncatedNoiseVariance(double variance, double threshold)
{
    return variance / truncatedNormalVariance(threshold / std::sqrt(variance));
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
        if (!uncertainty || !model.motion || !data.useEstimatedNoise || dof < 1 ||
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
        Matrix sandwich;
        revised.uncertainty.as<MotionUncertainty>()->covariance =
            estimated && sandwichCovariance(data, model, estimate.mask, count, sandwich)
                ? raisedToSandwich(modelBased, sandwich, static_cast<double>(count))
                : modelBased;
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
