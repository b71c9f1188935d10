// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 4 of Fig. 1, model refinement: the Gold Standard maximum-likelihood estimate on the inliers
// (Hartley & Zisserman, alg. 11.3) in its first-order form, Levenberg-Marquardt on the Sampson
// distances over a minimal parameterization of the model as it is: the 5-DoF motion when it has
// one, the 7-DoF F otherwise. The Gauss-Newton matrix at the optimum also gives the model's
// first-order covariance, sigma^2 (J^T J)^-1 (on a minimal sample: the paper's Sigma_p).

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"

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
    FundamentalTangent tangent;
    Eigen::Matrix3d pendingFn;

    FundamentalProblem(const Eigen::Matrix3d& T1_, const Eigen::Matrix3d& T2_,
                       const Eigen::Matrix3d& normalizedF)
        : T1(T1_), T2(T2_), Fn(FundamentalTangent(normalizedF).compose()), tangent(Fn)
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
        pendingFn = tangent.apply(delta);
        return toPixels(pendingFn);
    }
    void accept()
    {
        Fn = FundamentalTangent(pendingFn).compose();
        tangent = FundamentalTangent(Fn);
    }
};

double sampsonCost(const TwoViewData& data, const std::vector<int>& inliers,
                   const Eigen::Matrix3d& F)
{
    double cost = 0;
    for (int i : inliers)
        cost += sampsonDistanceSquared(F, data.points1[static_cast<size_t>(i)],
                                       data.points2[static_cast<size_t>(i)]);
    return cost;
}

// Gauss-Newton system J^T J, J^T r of the Sampson distances at the problem's current state.
template <class Problem>
void normalEquations(const TwoViewData& data, const std::vector<int>& inliers,
                     const Problem& problem,
                     Eigen::Matrix<double, Problem::kDof, Problem::kDof>& JtJ,
                     Eigen::Matrix<double, Problem::kDof, 1>& Jtr)
{
    constexpr int P = Problem::kDof;
    const Eigen::Matrix3d F = problem.current();
    Eigen::Matrix3d dF[P];
    problem.derivatives(dF);
    JtJ.setZero();
    Jtr.setZero();
    Eigen::Matrix<double, 1, P> g;
    double d = 0;
    for (int i : inliers) {
        if (!sampsonDistanceAndGradient<P>(F, dF, data.points1[static_cast<size_t>(i)],
                                           data.points2[static_cast<size_t>(i)], d, g))
            continue;
        JtJ.noalias() += g.transpose() * g;
        Jtr.noalias() += g.transpose() * d;
    }
}

// Levenberg-Marquardt with multiplicative damping on the diagonal. Returns the final cost.
template <class Problem>
double levenbergMarquardt(const TwoViewData& data, const std::vector<int>& inliers,
                          Problem& problem, int maxIterations)
{
    constexpr int P = Problem::kDof;
    double cost = sampsonCost(data, inliers, problem.current());
    double damping = 1e-3;
    Eigen::Matrix<double, P, P> JtJ;
    Eigen::Matrix<double, P, 1> Jtr;
    for (int iteration = 0; iteration < maxIterations; ++iteration) {
        normalEquations(data, inliers, problem, JtJ, Jtr);
        bool improved = false;
        while (damping < 1e12) {
            Eigen::Matrix<double, P, P> A = JtJ;
            A.diagonal() *= 1.0 + damping;
            const Eigen::Matrix<double, P, 1> delta = A.ldlt().solve(-Jtr);
            if (!delta.allFinite())
                break;
            const double candidateCost = sampsonCost(data, inliers, problem.propose(delta));
            if (candidateCost < cost) {
                problem.accept();
                improved = cost - candidateCost > 1e-12 * cost;
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

// sigma^2 (J^T J)^-1 at the problem's state, with the directions it refers to. None when J^T J is
// ill-conditioned: the points do not determine the model (e.g. a degenerate minimal sample).
template <class Problem>
void setUncertainty(const TwoViewData& data, const std::vector<int>& indices,
                    const Problem& problem, Model& model)
{
    constexpr int P = Problem::kDof;
    constexpr double kConditionLimit = 1e-10;
    Eigen::Matrix<double, P, P> JtJ;
    Eigen::Matrix<double, P, 1> Jtr;
    normalEquations(data, indices, problem, JtJ, Jtr);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, P, P>> eig(JtJ);
    model.uncertaintyDof = 0;
    if (!(eig.eigenvalues()(0) > kConditionLimit * eig.eigenvalues()(P - 1)))
        return;
    model.uncertaintyDof = P;
    model.covariance.setZero();
    model.covariance.template topLeftCorner<P, P>() =
        data.sigma * data.sigma * eig.eigenvectors() *
        eig.eigenvalues().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
    problem.derivatives(model.directions);
}

} // namespace

bool fitModelOn(const TwoViewData& data, const std::vector<int>& indices, int maxIterations,
                Model& model)
{
    if (model.hasMotion) {
        CV_Assert(data.calibrated);
        if (indices.size() < static_cast<size_t>(MotionProblem::kDof))
            return false;
        MotionProblem problem{data.Kinv, model.R, model.t, model.R, model.t};
        levenbergMarquardt(data, indices, problem, maxIterations);
        model.R = problem.R;
        model.t = problem.t;
        model.E = skew(model.t) * model.R;
        model.F = fundamentalFromEssential(model.E, data.Kinv);
        setUncertainty(data, indices, problem, model);
        return model.F.allFinite();
    }
    // A 7-DoF F needs 7 constraints (a 7-point sample determines it exactly).
    if (indices.size() < static_cast<size_t>(FundamentalProblem::kDof))
        return false;
    Eigen::Matrix3d T1, T2;
    if (!normalizingTransform(data.points1, indices, T1) ||
        !normalizingTransform(data.points2, indices, T2))
        return false;
    FundamentalProblem problem(T1, T2, T2.transpose().inverse() * model.F * T1.inverse());
    levenbergMarquardt(data, indices, problem, maxIterations);
    model.F = normalizeFundamental(problem.current());
    setUncertainty(data, indices, problem, model);
    return model.F.allFinite();
}

namespace {

class GoldStandardRefiner final : public Refiner
{
public:
    explicit GoldStandardRefiner(int maxIterations) : maxIterations_(maxIterations) {}

    bool refine(const TwoViewData& data, const std::vector<uchar>& mask, Model& model) override
    {
        // Reused, and sized for every point at once: local optimisation refines inside the
        // hypothesis loop, which must not allocate.
        inliers_.reserve(mask.size());
        inliers_.clear();
        for (size_t i = 0; i < mask.size(); ++i)
            if (mask[i])
                inliers_.push_back(static_cast<int>(i));
        return fitModelOn(data, inliers_, maxIterations_, model);
    }

private:
    int maxIterations_;
    std::vector<int> inliers_;
};

} // namespace

std::unique_ptr<Refiner> createGoldStandardRefiner(int maxIterations)
{
    return std::make_unique<GoldStandardRefiner>(maxIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
