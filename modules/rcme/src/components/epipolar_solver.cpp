// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model instantiation" of Fig. 1: the one adapter between the minimal solvers' math
// (src/solvers/, free functions on normalized points) and the loop's Models. It takes the
// sample's points to the frame the solver works in, calls it, and makes each solution a model in
// pixels, projected once:
// - solvers of F work on Hartley-normalized points (Hartley & Zisserman, alg. 11.1): the
//   normalized 8-point (8 parameters for a 7-DoF F, over-parameterized) and the 7-point (exact,
//   up to three F). With a camera matrix and `essentialHypotheses` each F is projected onto the
//   essential manifold so that every hypothesis is a motion; that projection no longer fits the
//   sample exactly (on noisy clean samples it keeps about half as many inliers as the rank-2 F,
//   measured on the generic scene), so Standard scores rank-2 F and recovers the motion from the
//   selected model only.
// - solvers of E work on rays K^-1 [x; 1]: the 5-point (exact for the 5 DoF of E, up to ten).
//   A solution no decomposition of which puts the whole sample in front of both cameras is not
//   a motion: dropped before it is scored on every point.
// A new solver is a file under src/solvers/ and one factory below.

#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"
#include "solvers/essential_five_point.hpp"
#include "solvers/fundamental_eight_point.hpp"
#include "solvers/fundamental_seven_point.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

//! What the adapter needs to know of a solver.
struct MinimalProblem
{
    int sampleSize;
    int maxSolutions;
    bool overParameterized;
    //! Solutions are E on camera rays (needs K); otherwise F on Hartley-normalized points.
    bool essential;
    //! The solutions are rank 3 in general: rank 2 is enforced when they stay F.
    bool enforceRankTwo;
    int (*solve)(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2, Eigen::Matrix3d* solutions);
};

constexpr int kMaxSampleSize = 8;
constexpr int kMaxSolutions = 10;

class EpipolarSolver final : public MinimalSolver
{
public:
    EpipolarSolver(const MinimalProblem& problem, bool essentialHypotheses)
        : problem_(problem), essentialHypotheses_(essentialHypotheses)
    {
        CV_Assert(problem.sampleSize <= kMaxSampleSize && problem.maxSolutions <= kMaxSolutions);
    }

    int sampleSize() const override { return problem_.sampleSize; }
    int maxSolutions() const override { return problem_.maxSolutions; }
    bool isOverParameterized() const override { return problem_.overParameterized; }
    std::unique_ptr<MinimalSolver> clone() const override
    {
        return std::make_unique<EpipolarSolver>(*this);
    }

    int estimate(const TwoViewData& data, const std::vector<int>& sample,
                 std::vector<Model>& models) override
    {
        models.clear();
        const int m = problem_.sampleSize;
        // E needs calibrated data (the factory never pairs such a solver with uncalibrated data).
        if (static_cast<int>(sample.size()) != m || (problem_.essential && !data.calibrated))
            return 0;
        Eigen::Matrix3d T1 = data.Kinv, T2 = data.Kinv;
        if (!problem_.essential &&
            !normalizingTransforms(data.points1, data.points2, sample, T1, T2))
            return 0;
        Eigen::Vector3d x1[kMaxSampleSize], x2[kMaxSampleSize];
        for (int k = 0; k < m; ++k) {
            const size_t i = static_cast<size_t>(sample[static_cast<size_t>(k)]);
            x1[k] = T1 * homogeneous(data.points1[i]);
            x2[k] = T2 * homogeneous(data.points2[i]);
        }
        Eigen::Matrix3d solutions[kMaxSolutions];
        const int count = problem_.solve(x1, x2, solutions);
        for (int s = 0; s < count; ++s) {
            Model model;
            Eigen::Matrix3d& E = std::get<FundamentalForm>(model.form).essential;
            if (problem_.essential) {
                if (!admitsCommonCheirality(solutions[s], x1, x2, m))
                    continue;
                E = normalizeFundamental(solutions[s]);
                model.F = fundamentalFromEssential(E, data.Kinv);
            } else if (data.calibrated && essentialHypotheses_) {
                E = essentialFromFundamental(T2.transpose() * solutions[s] * T1, data.K);
                model.F = fundamentalFromEssential(E, data.Kinv);
            } else {
                const Eigen::Matrix3d Fn =
                    problem_.enforceRankTwo ? closestRankTwo(solutions[s]) : solutions[s];
                model.F = normalizeFundamental(T2.transpose() * Fn * T1);
            }
            if (!model.F.allFinite() || !E.allFinite() ||
                (problem_.essential && isRepeated(E, models)))
                continue;
            models.push_back(model);
        }
        return static_cast<int>(models.size());
    }

private:
    // Two roots of the 5-point polynomial that polished onto the same E (a double root) give
    // one model; the 7-point solver drops repeated roots itself.
    static bool isRepeated(const Eigen::Matrix3d& E, const std::vector<Model>& models)
    {
        for (const Model& other : models)
            if ((other.essential() - E).norm() < 1e-12)
                return true;
        return false;
    }

    MinimalProblem problem_;
    bool essentialHypotheses_;
};

int solveEightPoint(const Eigen::Vector3d* x1, const Eigen::Vector3d* x2,
                    Eigen::Matrix3d* solutions)
{
    return fundamentalFromEightPoints(x1, x2, solutions[0]) ? 1 : 0;
}

} // namespace

std::unique_ptr<MinimalSolver> createEightPointSolver(bool essentialHypotheses)
{
    return std::make_unique<EpipolarSolver>(
        MinimalProblem{8, 1, true, false, true, solveEightPoint}, essentialHypotheses);
}

std::unique_ptr<MinimalSolver> createSevenPointSolver(bool essentialHypotheses)
{
    return std::make_unique<EpipolarSolver>(
        MinimalProblem{7, kMaxSevenPointSolutions, false, false, false, fundamentalFromSevenPoints},
        essentialHypotheses);
}

std::unique_ptr<MinimalSolver> createFivePointSolver()
{
    return std::make_unique<EpipolarSolver>(
        MinimalProblem{5, kMaxFivePointSolutions, false, true, false, essentialFromFivePoints},
        false);
}

} // namespace detail
} // namespace rcme
} // namespace cv
