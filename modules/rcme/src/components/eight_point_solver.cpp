// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model instantiation" of Fig. 1 with the normalized 8-point algorithm (Hartley &
// Zisserman, alg. 11.1): 8 parameters for a 7-DoF F, over-parameterized. Optionally, with a
// camera matrix, the result is projected onto the essential manifold so that every hypothesis is
// a motion (5 DoF). That projection no longer fits the sample exactly: on noisy clean samples
// it keeps about half as many inliers as the rank-2 F (measured on the generic scene), so the
// Standard method scores the rank-2 F and recovers the motion from the selected model only.

#include "framework/component_factories.hpp"
#include "geometry/epipolar.hpp"
#include "solvers/fundamental_eight_point.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class EightPointSolver final : public MinimalSolver
{
public:
    explicit EightPointSolver(bool essentialHypotheses) : essentialHypotheses_(essentialHypotheses)
    {
    }

    int sampleSize() const override { return 8; }
    int maxSolutions() const override { return 1; }
    bool isOverParameterized() const override { return true; }
    std::unique_ptr<MinimalSolver> clone() const override
    {
        return std::make_unique<EightPointSolver>(*this);
    }

    int estimate(const TwoViewData& data, const std::vector<int>& sample,
                 std::vector<Model>& models) override
    {
        models.clear();
        if (sample.size() != 8)
            return 0;
        Eigen::Matrix3d T1, T2;
        if (!normalizingTransform(data.points1, sample, T1) ||
            !normalizingTransform(data.points2, sample, T2))
            return 0;

        Eigen::Vector3d x1[8], x2[8];
        for (int k = 0; k < 8; ++k) {
            const size_t i = static_cast<size_t>(sample[static_cast<size_t>(k)]);
            x1[k] = T1 * homogeneous(data.points1[i]);
            x2[k] = T2 * homogeneous(data.points2[i]);
        }
        Eigen::Matrix3d Fn;
        if (!fundamentalFromEightPoints(x1, x2, Fn))
            return 0;

        Model model;
        if (data.calibrated && essentialHypotheses_) {
            model.E = essentialFromFundamental(T2.transpose() * Fn * T1, data.K);
            model.F = fundamentalFromEssential(model.E, data.Kinv);
        } else {
            model.F = normalizeFundamental(T2.transpose() * closestRankTwo(Fn) * T1);
        }
        if (!model.F.allFinite())
            return 0;
        models.push_back(model);
        return 1;
    }

private:
    bool essentialHypotheses_;
};

} // namespace

std::unique_ptr<MinimalSolver> createEightPointSolver(bool essentialHypotheses)
{
    return std::make_unique<EightPointSolver>(essentialHypotheses);
}

} // namespace detail
} // namespace rcme
} // namespace cv
