// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "drop_in/agreeing_points.hpp"

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/model.hpp"
#include "framework/model_space.hpp"
#include "geometry/epipolar.hpp"

#include <opencv2/core/eigen.hpp>

#include <numeric>

namespace cv {
namespace rcme {
namespace detail {

namespace {

constexpr int kRefineIterations = 20; // Params::refineIterations' default

Mat toMat(const Eigen::Matrix3d& m)
{
    Mat out;
    eigen2cv(m, out);
    return out;
}

// Calls `visit` with each subset of `size` of the indices 0..n-1, in lexicographic order.
template <class Visit> void forEachSubset(int n, int size, Visit visit)
{
    std::vector<int> subset(static_cast<size_t>(size));
    std::iota(subset.begin(), subset.end(), 0);
    while (true) {
        visit(subset);
        int k = size - 1;
        while (k >= 0 && subset[static_cast<size_t>(k)] == n - size + k)
            --k;
        if (k < 0)
            return;
        ++subset[static_cast<size_t>(k)];
        for (int j = k + 1; j < size; ++j)
            subset[static_cast<size_t>(j)] = subset[static_cast<size_t>(j - 1)] + 1;
    }
}

// The sum of the points' squared Sampson distances to `model`, or infinity when a point lies
// outside the inlier threshold or, with a camera matrix, behind a camera (the motion is then
// set from E by cheirality on all the points).
double costWhenAllAgree(const TwoViewData& data, Model& model)
{
    constexpr double kNone = std::numeric_limits<double>::infinity();
    const std::vector<uchar> all(static_cast<size_t>(data.size()), 1);
    if (data.calibrated &&
        (!recoverMotion(data, all, model) ||
         countPointsInFront(model.motion()->R, model.motion()->t, data.points1, data.points2,
                            data.Kinv, nullptr, nullptr, kNone) < data.size()))
        return kNone;
    double cost = 0;
    for (size_t i = 0; i < data.points1.size(); ++i) {
        const double d2 = sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]);
        if (!(d2 <= data.threshold * data.threshold))
            return kNone;
        cost += d2;
    }
    return cost;
}

// The model's matrix as the drop-in returns it: E with unit Frobenius norm, or F.
Mat modelMatrix(const TwoViewData& data, const Model& model)
{
    const Eigen::Matrix3d E = model.essential();
    return toMat(data.calibrated ? Eigen::Matrix3d(E / E.norm()) : model.F);
}

} // namespace

Mat modelOfAgreeingPoints(const TwoViewData& data, bool stackSolutions)
{
    const int n = data.size();
    const std::unique_ptr<MinimalSolver> solver =
        data.calibrated ? createFivePointSolver() : createSevenPointSolver(false);
    const int m = solver->sampleSize();
    if (n < m || n >= kDropInFewPoints)
        return Mat();
    // Every minimal subset's solutions, kept when all the points agree with them.
    std::vector<Model> models, agreeing;
    std::vector<double> costs;
    forEachSubset(n, m, [&](const std::vector<int>& subset) {
        solver->estimate(data, subset, models);
        for (Model& model : models) {
            const double cost = costWhenAllAgree(data, model);
            if (cost < std::numeric_limits<double>::infinity()) {
                agreeing.push_back(model);
                costs.push_back(cost);
            }
        }
    });
    if (agreeing.empty())
        return Mat();
    if (n == m) { // the data cannot choose among the solutions of their minimal problem
        if (!stackSolutions && agreeing.size() > 1)
            return Mat();
        Mat stacked;
        for (const Model& model : agreeing)
            stacked.push_back(modelMatrix(data, model));
        return stacked;
    }
    Model best =
        agreeing[static_cast<size_t>(std::min_element(costs.begin(), costs.end()) - costs.begin())];
    // Two distinct motions that every point agrees with: the points do not determine the motion.
    if (data.calibrated)
        for (const Model& model : agreeing)
            if (areDistinctMotions(model, best))
                return Mat();
    // The Gold Standard fit on all the points, kept when they all still agree with it.
    Model refined = best;
    std::vector<int> all(static_cast<size_t>(n));
    std::iota(all.begin(), all.end(), 0);
    if (fitModelOn(data, createModelSpace(data)->formOf(refined), all, kRefineIterations,
                   refined) &&
        costWhenAllAgree(data, refined) < std::numeric_limits<double>::infinity())
        best = refined;
    return modelMatrix(data, best);
}

} // namespace detail
} // namespace rcme
} // namespace cv
