// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 1(a) of Fig. 1(b), "model instantiation and uncertainty analysis": the hypotheses of a
// minimal solver, each given its motion (with a camera matrix: the essential matrix decomposed
// with cheirality on the sample) and the first-order covariance of its parameters from the m
// samples, Sigma_p = (J^T Sigma_S^-1 J)^-1 in a minimal parameterization (5-DoF motion, 7-DoF F).
// A sample whose information matrix is ill-conditioned is degenerate: its hypothesis is dropped.
// Optionally the hypothesis is first fitted to its own sample by Gauss-Newton, for which that
// covariance is exact to first order (Params::sampleFitIterations).

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class UncertainModelInstantiation final : public MinimalSolver
{
public:
    UncertainModelInstantiation(std::unique_ptr<MinimalSolver> solver,
                                std::shared_ptr<const ModelSpace> space, int fitIterations)
        : solver_(std::move(solver)), space_(std::move(space)), fitIterations_(fitIterations)
    {
    }

    int sampleSize() const override { return solver_->sampleSize(); }
    int maxSolutions() const override { return solver_->maxSolutions(); }
    bool isOverParameterized() const override { return solver_->isOverParameterized(); }
    std::unique_ptr<MinimalSolver> clone() const override
    {
        return std::make_unique<UncertainModelInstantiation>(solver_->clone(), space_,
                                                             fitIterations_);
    }

    int estimate(const TwoViewData& data, const std::vector<int>& sample,
                 std::vector<Model>& models) override
    {
        solver_->estimate(data, sample, models);
        size_t kept = 0;
        for (Model& model : models) {
            // Cheirality decided by the sample alone: the hypothesis knows nothing else.
            if (!space_->liftHypothesis(data, sample, model, samplePoints1_, samplePoints2_))
                continue;
            if (!fitModelOn(data, space_->formOf(model), sample, fitIterations_, model) ||
                !model.uncertainty.isKnown())
                continue;
            models[kept++] = model;
        }
        models.resize(kept);
        return static_cast<int>(kept);
    }

private:
    std::unique_ptr<MinimalSolver> solver_;
    std::shared_ptr<const ModelSpace> space_;
    int fitIterations_;
    std::vector<Eigen::Vector2d> samplePoints1_, samplePoints2_;
};

} // namespace

std::unique_ptr<MinimalSolver>
createUncertainModelInstantiation(std::unique_ptr<MinimalSolver> solver,
                                  std::shared_ptr<const ModelSpace> space, int fitIterations)
{
    return std::make_unique<UncertainModelInstantiation>(std::move(solver), std::move(space),
                                                         fitIterations);
}

} // namespace detail
} // namespace rcme
} // namespace cv
