// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model instantiation" of Fig. 1 with the 5-point algorithm for calibrated data: 5
// correspondences for the 5 DoF of E, so the sample is fitted exactly and the solver is not
// over-parameterized. The math is solvers/essential_five_point.cpp; this adapter takes the
// sample's points to normalized camera coordinates and makes each E a Model.

#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"
#include "solvers/essential_five_point.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class FivePointSolver final : public MinimalSolver
{
public:
    int sampleSize() const override { return 5; }
    int maxSolutions() const override { return 10; }
    bool isOverParameterized() const override { return false; }
    std::unique_ptr<MinimalSolver> clone() const override
    {
        return std::make_unique<FivePointSolver>(*this);
    }

    int estimate(const TwoViewData& data, const std::vector<int>& sample,
                 std::vector<Model>& models) override
    {
        models.clear();
        // Calibrated data only (the factory never pairs this solver with uncalibrated data).
        if (!data.calibrated || sample.size() != 5)
            return 0;

        Eigen::Vector3d q1[5], q2[5];
        for (int k = 0; k < 5; ++k) {
            const size_t i = static_cast<size_t>(sample[static_cast<size_t>(k)]);
            q1[k] = data.Kinv * homogeneous(data.points1[i]);
            q2[k] = data.Kinv * homogeneous(data.points2[i]);
        }
        Eigen::Matrix3d solutions[kMaxFivePointSolutions];
        const int count = essentialFromFivePoints(q1, q2, solutions);
        for (int k = 0; k < count; ++k) {
            // A solution no decomposition of which puts the whole sample in front of both cameras
            // is not a motion: dropped before it is scored on every point.
            if (!admitsCommonCheirality(solutions[k], q1, q2, 5))
                continue;
            Model model;
            model.E = normalizeFundamental(solutions[k]);
            model.F = fundamentalFromEssential(model.E, data.Kinv);
            if (!model.F.allFinite())
                continue;
            // Two roots that polished onto the same solution (a double root) give one model.
            bool repeated = false;
            for (const Model& other : models)
                repeated = repeated || (other.E - model.E).norm() < 1e-12;
            if (!repeated)
                models.push_back(model);
        }
        return static_cast<int>(models.size());
    }
};

} // namespace

std::unique_ptr<MinimalSolver> createFivePointSolver()
{
    return std::make_unique<FivePointSolver>();
}

} // namespace detail
} // namespace rcme
} // namespace cv
