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
    const Eigen::Matrix3d hypothesis = model.essential();
    const Eigen::Matrix3d E =
        hypothesis.isZero() ? essentialFromFundamental(model.F, data.K) : hypothesis;
    // A motion the decomposition fails on keeps what it tried last (the rejected model's).
    Motion decomposed = model.motion() ? *model.motion() : Motion();
    const int inFront = recoverMotionFromEssential(E, points1, points2, data.Kinv, selection,
                                                   decomposed.R, decomposed.t);
    if (inFront <= 0 && !model.motion())
        return false;
    if (inFront <= 0) {
        *model.motion() = decomposed;
        return false;
    }
    setMotion(data, decomposed, model);
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

Eigen::Matrix3d Model::essential() const
{
    if (const Motion* m = motion())
        return skew(m->t) * m->R;
    return std::get<FundamentalForm>(form).essential;
}

void setMotion(const TwoViewData& data, const Motion& motion, Model& model)
{
    model.form = motion;
    model.F = fundamentalFromEssential(skew(motion.t) * motion.R, data.Kinv);
}

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
    if (!a.motion() || !b.motion())
        return true;
    return rotationAngleDeg(a.motion()->R, b.motion()->R) > kDistinctRotationDeg ||
           directionAngleDeg(a.motion()->t, b.motion()->t) > kDistinctTranslationDeg;
}

} // namespace detail
} // namespace rcme
} // namespace cv
