// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "framework/components.hpp"
#include "geometry/epipolar.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// The motion, E and F from the decomposition of the model's E (or of K^T F K) that puts the most
// of the given points (all when `selection` is null) in front of both cameras.
bool setMotionByCheirality(const TwoViewData& data, const std::vector<Eigen::Vector2d>& points1,
                           const std::vector<Eigen::Vector2d>& points2,
                           const std::vector<uchar>* selection, Model& model)
{
    CV_Assert(data.calibrated);
    const Eigen::Matrix3d E =
        model.E.isZero() ? essentialFromFundamental(model.F, data.K) : model.E;
    // A motion the decomposition fails on keeps what it tried last (the rejected model's).
    Motion decomposed = model.motion.value_or(Motion());
    const int inFront = recoverMotionFromEssential(E, points1, points2, data.Kinv, selection,
                                                   decomposed.R, decomposed.t);
    if (inFront <= 0 && !model.motion)
        return false;
    model.motion = decomposed;
    if (inFront <= 0)
        return false;
    model.E = skew(decomposed.t) * decomposed.R;
    model.F = fundamentalFromEssential(model.E, data.Kinv);
    return true;
}

double rotationAngleDeg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B)
{
    const double c = std::max(-1.0, std::min(1.0, ((A * B.transpose()).trace() - 1.0) / 2.0));
    return std::acos(c) * 180.0 / CV_PI;
}

double directionAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    return std::acos(std::max(-1.0, std::min(1.0, a.dot(b)))) * 180.0 / CV_PI;
}

} // namespace

bool recoverMotion(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model)
{
    return setMotionByCheirality(data, data.points1, data.points2, &inliers, model);
}

bool recoverMotionFromSample(const TwoViewData& data, const std::vector<int>& sample, Model& model,
                             std::vector<Eigen::Vector2d>& points1,
                             std::vector<Eigen::Vector2d>& points2)
{
    points1.clear();
    points2.clear();
    for (int i : sample) {
        points1.push_back(data.points1[static_cast<size_t>(i)]);
        points2.push_back(data.points2[static_cast<size_t>(i)]);
    }
    return setMotionByCheirality(data, points1, points2, nullptr, model);
}

bool areDistinctMotions(const Model& a, const Model& b)
{
    constexpr double kDistinctRotationDeg = 5.0, kDistinctTranslationDeg = 15.0;
    return rotationAngleDeg(a.motion->R, b.motion->R) > kDistinctRotationDeg ||
           directionAngleDeg(a.motion->t, b.motion->t) > kDistinctTranslationDeg;
}

} // namespace detail
} // namespace rcme
} // namespace cv
