// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Input checking: every malformed argument is reported by name before any estimation starts.

#include "framework/two_view_data.hpp"
#include "framework/two_view_input.hpp"
#include "geometry/statistics.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

template <typename T>
void appendPoints(const Mat& m, int count, std::vector<Eigen::Vector2d>& out, const char* argName)
{
    const Mat flat = m.isContinuous() ? m : m.clone();
    const T* data = flat.ptr<T>();
    out.resize(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        const double x = static_cast<double>(data[2 * i]);
        const double y = static_cast<double>(data[2 * i + 1]);
        if (!std::isfinite(x) || !std::isfinite(y))
            CV_Error(Error::StsBadArg,
                     cv::format("%s: point %d has a non-finite coordinate", argName, i));
        out[static_cast<size_t>(i)] = Eigen::Vector2d(x, y);
    }
}

} // namespace

std::vector<Eigen::Vector2d> readPoints(InputArray points, const char* argName)
{
    if (points.empty())
        CV_Error(Error::StsBadArg, cv::format("%s is empty", argName));
    const Mat m = points.getMat();
    // Non-continuous input (a strided NumPy slice, a ROI) is accepted and copied below.
    const int count = m.checkVector(2, -1, /*requireContinuous=*/false);
    if (count <= 0)
        CV_Error(Error::StsBadArg,
                 cv::format("%s must be Nx2 (1 channel), Nx1 or 1xN (2 channels), got %dx%d with "
                            "%d channels",
                            argName, m.rows, m.cols, m.channels()));
    std::vector<Eigen::Vector2d> out;
    switch (m.depth()) {
    case CV_32F:
        appendPoints<float>(m, count, out, argName);
        break;
    case CV_64F:
        appendPoints<double>(m, count, out, argName);
        break;
    case CV_32S:
        appendPoints<int>(m, count, out, argName);
        break;
    default: { // the other depths OpenCV (and the Python module) accept: 8U/8S/16U/16S/16F
        Mat m64;
        m.convertTo(m64, CV_64F);
        appendPoints<double>(m64, count, out, argName);
        break;
    }
    }
    return out;
}

bool readCameraMatrix(InputArray cameraMatrix, const char* argName, Eigen::Matrix3d& K)
{
    if (cameraMatrix.empty())
        return false;
    const Mat m = cameraMatrix.getMat();
    if (m.rows != 3 || m.cols != 3 || m.channels() != 1)
        CV_Error(Error::StsBadArg, cv::format("%s must be 3x3 with one channel, got %dx%d with %d "
                                              "channels",
                                              argName, m.rows, m.cols, m.channels()));
    Mat k64; // any depth, as OpenCV and the Python module (an int32 K is common)
    m.convertTo(k64, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            K(r, c) = k64.at<double>(r, c);
    if (!K.allFinite())
        CV_Error(Error::StsBadArg, cv::format("%s has a non-finite entry", argName));
    if (K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) == 0)
        CV_Error(Error::StsBadArg,
                 cv::format("%s must have last row (0, 0, k) with k != 0", argName));
    K /= K(2, 2);
    if (!(std::abs(K.determinant()) > 1e-12 * std::pow(K.topLeftCorner<2, 2>().norm(), 2)) ||
        K(0, 0) == 0 || K(1, 1) == 0)
        CV_Error(Error::StsBadArg, cv::format("%s is singular (zero focal length)", argName));
    // A negative focal length mirrors the image: points behind the camera would pass
    // cheirality, so the motion would come out wrong without any error.
    if (K(0, 0) < 0 || K(1, 1) < 0)
        CV_Error(Error::StsBadArg,
                 cv::format("%s has a negative focal length (fx = %g, fy = %g); pass the "
                            "intrinsics of a camera with positive focal lengths",
                            argName, K(0, 0), K(1, 1)));
    return true;
}

Eigen::Matrix3d cameraMatrixFromFocal(double focal, Point2d pp)
{
    if (!std::isfinite(focal) || focal <= 0)
        CV_Error(Error::StsBadArg, "focal must be a positive finite number");
    if (!std::isfinite(pp.x) || !std::isfinite(pp.y))
        CV_Error(Error::StsBadArg, "pp must be finite");
    Eigen::Matrix3d K;
    K << focal, 0, pp.x, 0, focal, pp.y, 0, 0, 1;
    return K;
}

double inlierThreshold(const Params& params)
{
    // sqrt of the 95 % quantile of chi-square with 1 DoF: the Sampson distance of an inlier is
    // one-dimensional Gaussian noise with standard deviation sigma.
    constexpr double kChi2OneDof95Sqrt = 1.959963984540054;
    return params.threshold > 0 ? params.threshold : kChi2OneDof95Sqrt * params.sigma;
}

TwoViewData makeTwoViewData(InputArray points1, InputArray points2, InputArray cameraMatrix,
                            const Params& params)
{
    validateParams(params);
    TwoViewData data;
    data.points1 = readPoints(points1, "points1");
    data.points2 = readPoints(points2, "points2");
    if (data.points1.size() != data.points2.size())
        CV_Error(Error::StsUnmatchedSizes,
                 cv::format("points1 and points2 must hold the same number of points (%d vs %d)",
                            static_cast<int>(data.points1.size()),
                            static_cast<int>(data.points2.size())));
    data.calibrated = readCameraMatrix(cameraMatrix, "cameraMatrix", data.K);
    data.Kinv = data.K.inverse();
    data.sigma = params.sigma;
    data.threshold = inlierThreshold(params);
    data.consistencyBound = chiSquareQuantile(1.0 - params.alpha, params.consistencyDof);
    data.useEstimatedNoise = params.useEstimatedNoise;
    return data;
}

Eigen::Vector2d boundingBoxSize(const std::vector<Eigen::Vector2d>& points)
{
    if (points.empty())
        return Eigen::Vector2d::Zero();
    Eigen::Vector2d lo = points.front(), hi = points.front();
    for (const auto& x : points) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    return hi - lo;
}

void writeMask(const std::vector<uchar>& mask, OutputArray out)
{
    if (!out.needed())
        return;
    Mat(static_cast<int>(mask.size()), 1, CV_8U, const_cast<uchar*>(mask.data())).copyTo(out);
}

void maskIndices(const std::vector<uchar>& mask, std::vector<int>& indices)
{
    // Without a branch: an inlier mask is about as often 1 as 0 at random, and a branch on it
    // mispredicts every other point (7 ns a point on a million, against 1 ns).
    indices.resize(mask.size());
    size_t count = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        indices[count] = static_cast<int>(i);
        count += mask[i] != 0;
    }
    indices.resize(count);
}

namespace {

// Everything of the problem but its correspondences.
void copySettings(const TwoViewData& from, TwoViewData& to)
{
    to.calibrated = from.calibrated;
    to.K = from.K;
    to.Kinv = from.Kinv;
    to.sigma = from.sigma;
    to.threshold = from.threshold;
    to.consistencyBound = from.consistencyBound;
    to.useEstimatedNoise = from.useEstimatedNoise;
}

} // namespace

TwoViewData evenlySpacedSubset(const TwoViewData& data, size_t maxPoints)
{
    const size_t stride = subsetStride(data.points1.size(), maxPoints);
    if (stride == 1)
        return data;
    TwoViewData subset;
    copySettings(data, subset);
    for (size_t i = 0; i < data.points1.size(); i += stride) {
        subset.points1.push_back(data.points1[i]);
        subset.points2.push_back(data.points2[i]);
    }
    return subset;
}

} // namespace detail
} // namespace rcme
} // namespace cv
