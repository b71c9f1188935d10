// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The library's least-squares service: the Gold Standard maximum-likelihood fit (Hartley &
// Zisserman, alg. 11.3) in its first-order form, Levenberg-Marquardt on the Sampson distances
// over a minimal parameterization of the model in the form the caller names (ModelForm; the model
// space chooses it): the 5-DoF motion or the 7-DoF F. The Gauss-Newton matrix at the optimum also
// gives the model's first-order covariance, sigma^2 (J^T J)^-1 (on a minimal sample: the paper's
// Sigma_p). Used by the refiner (box 4 of Fig. 1), RCME's model instantiation and the ambiguity
// test's refits.

#include "estimation/model_fit.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/sampson_gradients.hpp"
#include "geometry/statistics.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The calibrated problem: the state is the motion; F = K^-T [t]x R K^-1.
struct MotionProblem
{
    static constexpr int kDof = MotionTangent::kDof;
    const Eigen::Matrix3d& Kinv;
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    Eigen::Matrix3d pendingR;
    Eigen::Vector3d pendingT;

    Eigen::Matrix3d fundamental(const Eigen::Matrix3d& Rm, const Eigen::Vector3d& tm) const
    {
        return Kinv.transpose() * skew(tm) * Rm * Kinv;
    }
    Eigen::Matrix3d current() const { return fundamental(R, t); }
    void derivatives(Eigen::Matrix3d dF[kDof]) const
    {
        MotionTangent(R, t).essentialDerivatives(dF);
        for (int k = 0; k < kDof; ++k)
            dF[k] = Kinv.transpose() * dF[k] * Kinv;
    }
    Eigen::Matrix3d propose(const Eigen::Matrix<double, kDof, 1>& delta)
    {
        MotionTangent(R, t).apply(delta, pendingR, pendingT);
        return fundamental(pendingR, pendingT);
    }
    void accept()
    {
        R = pendingR;
        t = pendingT;
    }
};

// The uncalibrated problem: the state is a rank-2 F in Hartley-normalized coordinates,
// F = T2^T Fn T1; in pixels the entries of F differ by orders of magnitude and the steps would
// be badly conditioned. The cost stays the pixel Sampson distance.
// The tangent (an SVD) is kept with Fn, which changes only on accept().
struct FundamentalProblem
{
    static constexpr int kDof = FundamentalTangent::kDof;
    Eigen::Matrix3d T1, T2;
    Eigen::Matrix3d Fn;
    FundamentalTangent tangent, pending;

    FundamentalProblem(const Eigen::Matrix3d& T1_, const Eigen::Matrix3d& T2_,
                       const Eigen::Matrix3d& normalizedF)
        : T1(T1_), T2(T2_), Fn(FundamentalTangent(normalizedF).compose()), tangent(Fn),
          pending(tangent)
    {
    }
    Eigen::Matrix3d toPixels(const Eigen::Matrix3d& normalized) const
    {
        return T2.transpose() * normalized * T1;
    }
    Eigen::Matrix3d current() const { return toPixels(Fn); }
    void derivatives(Eigen::Matrix3d dF[kDof]) const
    {
        tangent.derivatives(dF);
        for (int k = 0; k < kDof; ++k)
            dF[k] = toPixels(dF[k]);
    }
    Eigen::Matrix3d propose(const Eigen::Matrix<double, kDof, 1>& delta)
    {
        pending = tangent.moved(delta);
        return toPixels(pending.compose());
    }
    void accept()
    {
        tangent = pending;
        Fn = tangent.compose();
    }
};

// A fit's points as four coordinate arrays in the indices' order, for the block kernels: gathered
// once per fit, and every pass of its iterations reads them in place (gathered by index on each
// pass, or strided through a million points, they would be a scattered read per point). Per
// thread and reused: local optimisation fits inside the hypothesis loop, which must not
// allocate. Valid until the thread's next gathering; the functions below that gather do not call
// one another while they hold it.
struct GatheredPoints
{
    std::vector<double> x1, y1, x2, y2;

    size_t size() const { return x1.size(); }
    //! The number of points of the block that starts at `start` (at most kSampsonBlock).
    int blockSize(size_t start) const
    {
        return static_cast<int>(std::min<size_t>(kSampsonBlock, size() - start));
    }
};

// indices[0], indices[stride], indices[2 stride], ...: every one by default, or the evenly spaced
// subset a large fit iterates on (kMaxIteratedPoints, subsetStride).
const GatheredPoints& gatherPoints(const TwoViewData& data, const std::vector<int>& indices,
                                   size_t stride = 1)
{
    thread_local GatheredPoints gathered;
    // Room for every point of the data at once: local optimisation's growing inlier sets then
    // never reallocate.
    if (gathered.x1.capacity() < data.points1.size())
        for (std::vector<double>* coordinates :
             {&gathered.x1, &gathered.y1, &gathered.x2, &gathered.y2})
            coordinates->reserve(data.points1.size());
    const size_t n = (indices.size() + stride - 1) / stride;
    gathered.x1.resize(n);
    gathered.y1.resize(n);
    gathered.x2.resize(n);
    gathered.y2.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const auto i = static_cast<size_t>(indices[k * stride]);
        gathered.x1[k] = data.points1[i].x();
        gathered.y1[k] = data.points1[i].y();
        gathered.x2[k] = data.points2[i].x();
        gathered.y2[k] = data.points2[i].y();
    }
    return gathered;
}

// Least squares: every point weighs alike.
struct SquaredLoss
{
    static double cost(double squared) { return squared; }
};

/* The Cauchy loss s^2 log(1 + d^2 / s^2) of the robust polish: a point well inside the noise
weighs as in least squares, one at a few s counts less and less (weight 1 / (1 + d^2 / s^2)),
so a few wide residuals among the inliers do not pull the fit. */
struct CauchyLoss
{
    double scale2;
    double cost(double squared) const { return scale2 * std::log1p(squared / scale2); }
    double weight(double squared) const { return 1.0 / (1.0 + squared / scale2); }
};

// The sum of the loss of the Sampson distances, in the inliers' order.
template <class Loss = SquaredLoss>
double sampsonCost(const GatheredPoints& points, const Eigen::Matrix3d& F,
                   const Loss& loss = Loss())
{
    double squared[kSampsonBlock];
    double cost = 0;
    for (size_t start = 0; start < points.size(); start += kSampsonBlock) {
        const int count = points.blockSize(start);
        sampsonDistancesSquaredOfBlock(F, &points.x1[start], &points.y1[start], &points.x2[start],
                                       &points.y2[start], count, squared);
        for (int j = 0; j < count; ++j)
            cost += loss.cost(squared[j]);
    }
    return cost;
}

// Scales each point's distance and gradient by the square root of its weight: the normal
// equations then sum w g^T g and w g^T d (iteratively reweighted least squares). Least squares
// leaves them as they are.
inline void weighBlock(const SquaredLoss&, int, int, double*, double*) {}

inline void weighBlock(const CauchyLoss& loss, int parameters, int count, double* distance,
                       double* gradients)
{
    for (int j = 0; j < count; ++j) {
        const double root = std::sqrt(loss.weight(distance[j] * distance[j]));
        distance[j] *= root;
        for (int k = 0; k < parameters; ++k)
            gradients[k * kSampsonBlock + j] *= root;
    }
}

// Gauss-Newton system J^T J, J^T r of the Sampson distances at the problem's current state. The
// distances and gradients come a block of points at a time (sampsonGradientsOfBlock, vectorized;
// the bits of sampsonDistanceAndGradient's per point), and so do the sums of their products
// (accumulateNormalEquations: the upper triangle, in four partial sums per entry).
template <class Problem, class Loss = SquaredLoss>
void normalEquations(const GatheredPoints& points, const Problem& problem,
                     Eigen::Matrix<double, Problem::kDof, Problem::kDof>& JtJ,
                     Eigen::Matrix<double, Problem::kDof, 1>& Jtr, const Loss& loss = Loss())
{
    constexpr int P = Problem::kDof;
    constexpr int B = kSampsonBlock;
    const Eigen::Matrix3d F = problem.current();
    Eigen::Matrix3d dF[P];
    problem.derivatives(dF);
    double distance[B], gradients[P * B];
    uchar valid[B];
    double normal[P][P + 1] = {};
    for (size_t start = 0; start < points.size(); start += B) {
        const int count = points.blockSize(start);
        sampsonGradientsOfBlock(F, dF, P, &points.x1[start], &points.y1[start], &points.x2[start],
                                &points.y2[start], count, distance, gradients, valid);
        weighBlock(loss, P, count, distance, gradients);
        accumulateNormalEquations(P, distance, gradients, count, &normal[0][0]);
    }
    for (int a = 0; a < P; ++a) {
        Jtr(a) = normal[a][P];
        for (int b = a; b < P; ++b)
            JtJ(a, b) = JtJ(b, a) = normal[a][b];
    }
}

// A step that lowers the cost by less than this share of it is the last. The cost is about
// n sigma^2, so such a step moves the model by about sqrt(1e-8 n) of its standard deviations
// (0.003 at n = 1000); the iterations that used to follow it (to 1e-12) were a fifth of all
// (doc/performance.md, "Levenberg-Marquardt's last steps").
constexpr double kNegligibleCostDecrease = 1e-8;

// Levenberg-Marquardt with multiplicative damping on the diagonal, on the loss's reweighted
// system. Returns the final cost.
template <class Problem, class Loss = SquaredLoss>
double levenbergMarquardt(const GatheredPoints& points, Problem& problem, int maxIterations,
                          const Loss& loss = Loss())
{
    constexpr int P = Problem::kDof;
    double cost = sampsonCost(points, problem.current(), loss);
    double damping = 1e-3;
    Eigen::Matrix<double, P, P> JtJ;
    Eigen::Matrix<double, P, 1> Jtr;
    for (int iteration = 0; iteration < maxIterations; ++iteration) {
        normalEquations(points, problem, JtJ, Jtr, loss);
        bool improved = false;
        while (damping < 1e12) {
            Eigen::Matrix<double, P, P> A = JtJ;
            A.diagonal() *= 1.0 + damping;
            const Eigen::Matrix<double, P, 1> delta = A.ldlt().solve(-Jtr);
            if (!delta.allFinite())
                break;
            const double candidateCost = sampsonCost(points, problem.propose(delta), loss);
            if (candidateCost < cost) {
                problem.accept();
                improved = cost - candidateCost > kNegligibleCostDecrease * cost;
                cost = candidateCost;
                damping = std::max(1e-9, damping * 0.1);
                break;
            }
            damping *= 10;
        }
        if (!improved)
            break;
    }
    return cost;
}

// A large fit iterates on an evenly spaced subset (kMaxIteratedPoints, two_view_data.hpp); the
// final estimate then takes a few more iterations on every point.
constexpr int kFullSetIterations = 3;

template <class Problem>
void finishOnEveryPoint(const TwoViewData& data, const std::vector<int>& inliers, Problem& problem,
                        int maxIterations)
{
    if (inliers.size() > kMaxIteratedPoints)
        levenbergMarquardt(gatherPoints(data, inliers), problem,
                           std::min(maxIterations, kFullSetIterations));
}

template <class Problem>
void leastSquares(const TwoViewData& data, const std::vector<int>& inliers, Problem& problem,
                  int maxIterations, bool finish)
{
    levenbergMarquardt(gatherPoints(data, inliers, subsetStride(inliers.size())), problem,
                       maxIterations);
    if (finish)
        finishOnEveryPoint(data, inliers, problem, maxIterations);
}

// Which covariance a fit gets: the stated sigma's sigma^2 (J^T J)^-1 (a hypothesis, a minimal
// sample: the paper's Sigma_p), or the final estimate's (see finalUncertainty).
enum class Uncertainty
{
    kStatedNoise,
    kFinalEstimate
};

// sigma^2 (J^T J)^-1 at the problem's state, with the directions it refers to, returned. None
// when J^T J is ill-conditioned: the points do not determine the model (e.g. a degenerate minimal
// sample). Unless everyPoint (the final estimate), a large set gives J^T J from its evenly spaced
// subset, scaled to the whole set: a hypothesis's or a decision's covariance needs no more.
template <class Problem>
TangentUncertainty<Problem::kDof>*
setUncertainty(const TwoViewData& data, const std::vector<int>& indices, const Problem& problem,
               Model& model, bool everyPoint = true)
{
    constexpr int P = Problem::kDof;
    constexpr double kConditionLimit = 1e-10;
    Eigen::Matrix<double, P, P> JtJ;
    Eigen::Matrix<double, P, 1> Jtr;
    if (everyPoint) {
        normalEquations(gatherPoints(data, indices), problem, JtJ, Jtr);
    } else {
        const GatheredPoints& subset = gatherPoints(data, indices, subsetStride(indices.size()));
        normalEquations(subset, problem, JtJ, Jtr);
        if (subset.size() < indices.size())
            JtJ *= static_cast<double>(indices.size()) / static_cast<double>(subset.size());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, P, P>> eig(JtJ);
    model.uncertainty.reset();
    if (!(eig.eigenvalues()(0) > kConditionLimit * eig.eigenvalues()(P - 1)))
        return nullptr;
    auto& uncertainty = model.uncertainty.template emplace<TangentUncertainty<P>>();
    uncertainty.covariance = data.sigma * data.sigma * eig.eigenvectors() *
                             eig.eigenvalues().cwiseInverse().asDiagonal() *
                             eig.eigenvectors().transpose();
    problem.derivatives(uncertainty.directions);
    return &uncertainty;
}

// The final estimate's noise and covariance. The noise comes from the inliers' Sampson residuals
// with the fit's degrees of freedom removed (n - dof) and the band's truncation undone: the band
// |d| < threshold keeps only the central part of the Gaussian, whose mean square alone would
// underestimate sigma^2 (by 24 % at 1.96 sigma). The fit is least squares on the points inside
// the band, i.e. an M-estimator with psi(d) = d 1{|d| < c}; its (sandwich) covariance is
// sigma^2 / h(c / sigma) (J^T J)^-1 with h = truncatedNormalVariance (the points a step of the
// model would push across the band's edge take their information with them), 1.32 times the
// plain sigma^2 (J^T J)^-1 at 1.96 sigma.
template <class Problem>
void setFinalUncertainty(const TwoViewData& data, const std::vector<int>& indices,
                         const Problem& problem, Model& model)
{
    TangentUncertainty<Problem::kDof>* uncertainty = setUncertainty(data, indices, problem, model);
    const int dof = static_cast<int>(indices.size()) - Problem::kDof;
    model.noiseSigma =
        dof > 0
            ? noiseFromTruncatedResiduals(
                  sampsonCost(gatherPoints(data, indices), problem.current()) / dof, data.threshold)
            : std::numeric_limits<double>::quiet_NaN();
    if (!uncertainty)
        return;
    const double sigma =
        usesEstimatedNoise(data, model.noiseSigma, dof) ? model.noiseSigma : data.sigma;
    uncertainty->covariance *=
        sigma * sigma / (data.sigma * data.sigma * truncatedNormalVariance(data.threshold / sigma));
}

// A point that carries this share of the information on some direction of the model outweighs
// all the others together there (leverage h > 1/2): they cannot confirm that it is an inlier.
constexpr double kMaxLeverage = 0.5;

// Removes from `indices` the inliers the others do not confirm, returns whether any was removed.
// A point's residual d at a fit it took part in has variance sigma^2 (1 - h), h its leverage, so
// the band's test on d is lax for a point of high leverage (it drags the fit onto itself): an
// outlier in the band near an epipole or at a depth far from the scene's takes over directions
// of the motion and makes its covariance confident where it is wrong. Such a point must pass the
// band on its studentized residual, |d| / sqrt(1 - h) < threshold, and have h <= 1/2.
// One pass, at the fit on all of `indices`: a point that shared a direction with a dropped one
// takes over its share in the refit and is kept, with a leverage up to near 1 in the final mask
// (doc/architecture.md, "Final fit and covariance"). Repeated, the rule would strip a direction
// that few points observe one point at a time, true inliers included.
template <class Problem>
bool dropUnconfirmedInliers(const TwoViewData& data, const Problem& problem,
                            std::vector<int>& indices)
{
    constexpr int P = Problem::kDof;
    constexpr int B = kSampsonBlock;
    const GatheredPoints& points = gatherPoints(data, indices);
    Eigen::Matrix<double, P, P> JtJ;
    Eigen::Matrix<double, P, 1> Jtr;
    normalEquations(points, problem, JtJ, Jtr);
    const Eigen::LDLT<Eigen::Matrix<double, P, P>> information(JtJ);
    if (information.info() != Eigen::Success)
        return false;
    const Eigen::Matrix3d F = problem.current();
    Eigen::Matrix3d dF[P];
    problem.derivatives(dF);
    // h = g^T (J^T J)^-1 g = w^T D^+ w with w = L^-1 P g (the factors P^T L D L^T P = J^T J; D^+
    // inverts the pivots that LDLT's solve inverts, the others are zero), a block of points at a
    // time: one triangular solve per point, vectorized over the block, in place of a solve per
    // point.
    const Eigen::Matrix<double, P, P> L = information.matrixL();
    double inverseD[P];
    int permuted[P];
    for (int k = 0; k < P; ++k) {
        const double pivot = information.vectorD()(k);
        inverseD[k] = std::abs(pivot) > std::numeric_limits<double>::min() ? 1.0 / pivot : 0.0;
        permuted[k] = k;
    }
    for (int k = 0; k < P; ++k)
        std::swap(permuted[k], permuted[information.transpositionsP().coeff(k)]);
    const double threshold2 = data.threshold * data.threshold;
    double distance[B], gradients[P * B], w[P][B], leverage[B];
    uchar valid[B];
    // Kept indices are written back in place: the k-th kept is never past the point read.
    size_t kept = 0;
    for (size_t start = 0; start < points.size(); start += B) {
        const int count = points.blockSize(start);
        sampsonGradientsOfBlock(F, dF, P, &points.x1[start], &points.y1[start], &points.x2[start],
                                &points.y2[start], count, distance, gradients, valid);
        for (int j = 0; j < count; ++j)
            leverage[j] = 0;
        for (int k = 0; k < P; ++k) {
            const double* g = &gradients[permuted[k] * B];
            for (int j = 0; j < count; ++j) {
                double value = g[j];
                for (int m = 0; m < k; ++m)
                    value -= L(k, m) * w[m][j];
                w[k][j] = value;
                leverage[j] += value * value * inverseD[k];
            }
        }
        for (int j = 0; j < count; ++j) {
            const double h = leverage[j], d = distance[j];
            // A point without a distance is not judged.
            const bool confirmed =
                !valid[j] || !(h > kMaxLeverage || d * d > threshold2 * (1.0 - h));
            if (confirmed)
                indices[kept++] = indices[start + static_cast<size_t>(j)];
        }
    }
    const bool removed = kept < indices.size();
    indices.resize(kept);
    return removed;
}

template <class Problem>
void setUncertaintyFor(Uncertainty kind, const TwoViewData& data, const std::vector<int>& indices,
                       const Problem& problem, Model& model)
{
    if (kind == Uncertainty::kFinalEstimate)
        setFinalUncertainty(data, indices, problem, model);
    else
        setUncertainty(data, indices, problem, model, /*everyPoint=*/false);
}

// Least squares on `indices`; the final estimate is refitted without the inliers the others do
// not confirm, when that leaves enough points to determine it.
template <class Problem>
void fitProblem(const TwoViewData& data, const std::vector<int>& indices, int maxIterations,
                Uncertainty uncertainty, Problem& problem, Model& model,
                std::vector<int>* confirmed)
{
    const bool final = uncertainty == Uncertainty::kFinalEstimate;
    // On a large set the iterations on every point wait until the inliers are settled.
    leastSquares(data, indices, problem, maxIterations, final && !confirmed);
    if (final && confirmed) {
        *confirmed = indices;
        if (dropUnconfirmedInliers(data, problem, *confirmed) &&
            confirmed->size() >= 2 * static_cast<size_t>(Problem::kDof)) {
            leastSquares(data, *confirmed, problem, maxIterations, true);
            setFinalUncertainty(data, *confirmed, problem, model);
            return;
        }
        *confirmed = indices;
        finishOnEveryPoint(data, indices, problem, maxIterations);
    }
    setUncertaintyFor(uncertainty, data, indices, problem, model);
}

// `confirmed` (final estimate only): the points the fit ends up using.
bool fitModel(const TwoViewData& data, ModelForm form, const std::vector<int>& indices,
              int maxIterations, Uncertainty uncertainty, Model& model,
              std::vector<int>* confirmed = nullptr)
{
    if (form == ModelForm::kMotion) {
        CV_Assert(data.calibrated && model.motion());
        if (indices.size() < static_cast<size_t>(MotionProblem::kDof))
            return false;
        const Motion& motion = *model.motion();
        MotionProblem problem{data.Kinv, motion.R, motion.t, motion.R, motion.t};
        fitProblem(data, indices, maxIterations, uncertainty, problem, model, confirmed);
        setMotion(data, Motion{problem.R, problem.t}, model);
        return model.F.allFinite();
    }
    // A 7-DoF F needs 7 constraints (a 7-point sample determines it exactly).
    if (indices.size() < static_cast<size_t>(FundamentalProblem::kDof))
        return false;
    Eigen::Matrix3d T1, T2;
    if (!normalizingTransforms(data.points1, data.points2, indices, T1, T2))
        return false;
    FundamentalProblem problem(T1, T2, T2.transpose().inverse() * model.F * T1.inverse());
    fitProblem(data, indices, maxIterations, uncertainty, problem, model, confirmed);
    model.F = normalizeFundamental(problem.current());
    return model.F.allFinite();
}

// CauchyVarianceFactor (model_fit.hpp) of the Sampson distances of `indices` under F.
double cauchyInefficiency(const TwoViewData& data, const std::vector<int>& indices,
                          const Eigen::Matrix3d& F, const CauchyLoss& loss)
{
    const GatheredPoints& points = gatherPoints(data, indices);
    double squared[kSampsonBlock];
    CauchyVarianceFactor factor(loss.scale2);
    for (size_t start = 0; start < points.size(); start += kSampsonBlock) {
        const int count = points.blockSize(start);
        sampsonDistancesSquaredOfBlock(F, &points.x1[start], &points.y1[start], &points.x2[start],
                                       &points.y2[start], count, squared);
        for (int j = 0; j < count; ++j)
            factor.add(squared[j]);
    }
    return factor.value();
}

} // namespace

void CauchyVarianceFactor::add(double squared)
{
    const double w = 1.0 / (1.0 + squared / scale2_);
    influence2_ += squared * w * w;
    curvature_ += (1.0 - squared / scale2_) * w * w;
    residual2_ += squared;
    count_ += 1.0;
}

double CauchyVarianceFactor::value() const
{
    if (!(curvature_ > 0 && residual2_ > 0))
        return std::numeric_limits<double>::quiet_NaN();
    return count_ * count_ * influence2_ / (curvature_ * curvature_ * residual2_);
}

// Fewest residual degrees of freedom (inliers minus the model's) for the estimated noise to
// replace the stated sigma: from 30 on, the estimate's relative standard error is below ~15 %.
constexpr int kMinNoiseDof = 30;

bool usesEstimatedNoise(const TwoViewData& data, double noiseSigma, int residualDof)
{
    return data.useEstimatedNoise && residualDof >= kMinNoiseDof && std::isfinite(noiseSigma);
}

bool fitModelOn(const TwoViewData& data, ModelForm form, const std::vector<int>& indices,
                int maxIterations, Model& model)
{
    return fitModel(data, form, indices, maxIterations, Uncertainty::kStatedNoise, model);
}

bool fitFinalModelOn(const TwoViewData& data, ModelForm form, const std::vector<int>& indices,
                     int maxIterations, Model& model, std::vector<int>& confirmed)
{
    return fitModel(data, form, indices, maxIterations, Uncertainty::kFinalEstimate, model,
                    &confirmed);
}

bool polishFinalMotionOn(const TwoViewData& data, const std::vector<int>& indices, double lossScale,
                         int maxIterations, Model& model)
{
    constexpr int P = MotionProblem::kDof;
    // A large set is left as least squares fitted it: what a loss of the residuals' tails gains
    // shrinks with the number of inliers, and every iteration on them costs (10^6 matches).
    // The loss's precision against least squares is judged from the residuals' moments, which
    // need the residual degrees of freedom the noise estimate needs (13 points: a noisy ratio
    // that kept a polish 2 deg off where least squares was within 1, the OpenCV parity test).
    if (!data.calibrated || !model.motion() ||
        static_cast<int>(indices.size()) - P < kMinNoiseDof ||
        indices.size() > kMaxIteratedPoints || !(lossScale > 0))
        return false;
    const CauchyLoss loss{lossScale * lossScale};
    const Motion& motion = *model.motion();
    MotionProblem problem{data.Kinv, motion.R, motion.t, motion.R, motion.t};
    levenbergMarquardt(gatherPoints(data, indices), problem, maxIterations, loss);
    const double inefficiency = cauchyInefficiency(data, indices, problem.current(), loss);
    if (!(inefficiency < 1.0))
        return false;
    Model polished = model;
    setFinalUncertainty(data, indices, problem, polished);
    if (!polished.uncertainty.as<MotionUncertainty>())
        return false;
    polished.polishLossScale = lossScale;
    setMotion(data, Motion{problem.R, problem.t}, polished);
    if (!polished.F.allFinite())
        return false;
    model = polished;
    return true;
}

} // namespace detail
} // namespace rcme
} // namespace cv
