// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box "model instantiation" of Fig. 1 with the normalized 8-point algorithm (Hartley &
// Zisserman, alg. 11.1): 8 parameters for a 7-DoF F, over-parameterized. Optionally, with a
// camera matrix, the result is projected onto the essential manifold so that every hypothesis is
// a motion (5 DoF). That projection no longer fits the sample exactly: on noisy clean samples
// it keeps about half as many inliers as the rank-2 F (measured on the generic scene), so the
// Standard method scores the rank-2 F and recovers the motion from the selected model only.

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"

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
        Eigen::Matrix3d T1, T2;
        if (!normalizingTransform(data.points1, sample, T1) ||
            !normalizingTransform(data.points2, sample, T2))
            return 0;

        // x2^T F x1 = 0 as a row of A times the row-major entries of F.
        Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
        for (int i : sample) {
            const Eigen::Vector3d a = T1 * homogeneous(data.points1[static_cast<size_t>(i)]);
            const Eigen::Vector3d b = T2 * homogeneous(data.points2[static_cast<size_t>(i)]);
            Eigen::Matrix<double, 9, 1> row;
            row << b.x() * a, b.y() * a, a;
            AtA.selfadjointView<Eigen::Lower>().rankUpdate(row);
        }
        AtA = AtA.selfadjointView<Eigen::Lower>();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(AtA);
        const Eigen::Matrix<double, 9, 1> values = eig.eigenvalues();
        // A second (near) null direction means the sample does not determine F: coincident,
        // collinear or otherwise degenerate points.
        if (!(values(1) > 1e-10 * values(8)))
            return 0;
        const Eigen::Matrix<double, 9, 1> f = eig.eigenvectors().col(0);
        Eigen::Matrix3d Fn;
        Fn << f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8);

        Model model;
        if (data.calibrated && essentialHypotheses_) {
            model.E = essentialFromFundamental(T2.transpose() * Fn * T1, data.K);
            model.F = fundamentalFromEssential(model.E, data.Kinv);
        } else {
            Eigen::JacobiSVD<Eigen::Matrix3d> svd(Fn, Eigen::ComputeFullU | Eigen::ComputeFullV);
            Eigen::Vector3d sv = svd.singularValues();
            sv(2) = 0;
            const Eigen::Matrix3d rank2 =
                svd.matrixU() * sv.asDiagonal() * svd.matrixV().transpose();
            model.F = normalizeFundamental(T2.transpose() * rank2 * T1);
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
