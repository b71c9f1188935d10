// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Motion error metrics (the paper's dq and dt, Sec. V-B.1, and the angular errors) and the
// motion covariance in a pose graph's convention.

#include "precomp.hpp"

#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"

#include <opencv2/core/eigen.hpp>

namespace cv {
namespace rcme {

MotionError::MotionError()
    : dq(std::numeric_limits<double>::quiet_NaN()), dt(std::numeric_limits<double>::quiet_NaN()),
      rotationDeg(std::numeric_limits<double>::quiet_NaN()),
      translationDeg(std::numeric_limits<double>::quiet_NaN())
{
}

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Largest deviation of a singular value from 1 still accepted as a rotation: loose enough for
// rotations stored in CV_16F or CV_32F, tight enough to reject scaled or arbitrary matrices.
const double kRotationTolerance = 1e-2;

bool isFloatDepth(int depth)
{
    return depth == CV_16F || depth == CV_32F || depth == CV_64F;
}

// The nearest rotation (polar factor) of a 3x3 matrix that is close to one.
Matrix3d readRotation(InputArray input, const char* function, const char* name)
{
    const Mat m = input.getMat();
    if (m.empty() || m.dims != 2 || m.rows != 3 || m.cols != 3 || m.channels() != 1 ||
        !isFloatDepth(m.depth()))
        CV_Error(
            Error::StsBadArg,
            format("%s: %s must be a 3x3 single-channel floating-point matrix", function, name));
    Mat md;
    m.convertTo(md, CV_64F);
    Matrix3d M;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            M(r, c) = md.at<double>(r, c);
    if (!M.allFinite())
        CV_Error(Error::StsBadArg, format("%s: %s has non-finite entries", function, name));

    Eigen::JacobiSVD<Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Vector3d s = svd.singularValues();
    if ((s.array() - 1.0).abs().maxCoeff() > kRotationTolerance)
        CV_Error(Error::StsBadArg,
                 format("%s: %s is not a rotation matrix (singular values %g, %g, %g)", function,
                        name, s(0), s(1), s(2)));
    const Matrix3d Q = svd.matrixU() * svd.matrixV().transpose();
    if (Q.determinant() < 0)
        CV_Error(Error::StsBadArg,
                 format("%s: %s is not a rotation matrix (determinant < 0)", function, name));
    return Q;
}

// A non-zero 3-vector (3x1, 1x3, or 1x1 with three channels; OpenCV 5 also makes a
// one-dimensional Mat of three, e.g. from a NumPy array of shape (3,)), returned with unit length.
Vector3d readDirection(InputArray input, const char* function, const char* name)
{
    const Mat m = input.getMat();
    const bool shapeOk =
        !m.empty() && isFloatDepth(m.depth()) && (m.checkVector(1) == 3 || m.checkVector(3) == 1);
    if (!shapeOk)
        CV_Error(Error::StsBadArg,
                 format("%s: %s must be a floating-point 3-vector (3x1 or 1x3)", function, name));
    Mat md;
    m.reshape(1, 3).convertTo(md, CV_64F);
    const Vector3d v(md.at<double>(0), md.at<double>(1), md.at<double>(2));
    if (!v.allFinite())
        CV_Error(Error::StsBadArg, format("%s: %s has non-finite entries", function, name));
    const double len = v.norm();
    if (!(len > 0))
        CV_Error(Error::StsBadArg, format("%s: %s must have non-zero length", function, name));
    return v / len;
}

// Unit quaternion as a 4-vector (x, y, z, w); Eigen picks the numerically safest branch.
Eigen::Vector4d toQuaternion(const Matrix3d& R)
{
    Eigen::Quaterniond q(R);
    q.normalize();
    return q.coeffs();
}

} // namespace

MotionError compareMotion(InputArray R, InputArray t, InputArray Rgt, InputArray tgt)
{
    const char* f = "compareMotion";
    const Matrix3d Re = readRotation(R, f, "R");
    const Vector3d te = readDirection(t, f, "t");
    const Matrix3d Rg = readRotation(Rgt, f, "Rgt");
    const Vector3d tg = readDirection(tgt, f, "tgt");

    MotionError err;
    const Eigen::Vector4d q = toQuaternion(Re);
    const Eigen::Vector4d qg = toQuaternion(Rg);
    // q and -q are the same rotation.
    err.dq = std::min((q - qg).norm(), (q + qg).norm());
    err.dt = (te - tg).norm();

    // atan2 of the sine and cosine parts instead of acos of the trace: accurate for small
    // angles, where acos loses half the digits, and needs no clamping.
    const Matrix3d D = Rg.transpose() * Re;
    const Vector3d axis(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
    const double rotRad = std::atan2(0.5 * axis.norm(), 0.5 * (D.trace() - 1.0));
    err.rotationDeg = rotRad * 180.0 / CV_PI;

    const double transRad = std::atan2(te.cross(tg).norm(), te.dot(tg));
    err.translationDeg = transRad * 180.0 / CV_PI;
    return err;
}

Mat poseCovariance(InputArray R, InputArray t, InputArray covariance, double scaleStd, bool inverse)
{
    const char* f = "poseCovariance";
    const Matrix3d Rm = readRotation(R, f, "R");
    const Vector3d tu = readDirection(t, f, "t");
    const Mat c = covariance.getMat();
    if (c.dims != 2 || c.rows != 5 || c.cols != 5 || c.channels() != 1 || !isFloatDepth(c.depth()))
        CV_Error(Error::StsBadArg, "poseCovariance: covariance must be a 5x5 floating-point "
                                   "matrix (Report::covariance)");
    if (!(scaleStd >= 0) || !std::isfinite(scaleStd))
        CV_Error(Error::StsBadArg, "poseCovariance: scaleStd must be finite and >= 0");
    Mat c64;
    c.convertTo(c64, CV_64F);
    Eigen::Matrix<double, 5, 5> tangent;
    cv2eigen(c64, tangent);
    if (!tangent.allFinite())
        CV_Error(Error::StsBadArg, "poseCovariance: covariance has non-finite entries");

    // xi = J theta: omega is shared, and v = R^T B beta (t + B beta, to first order on the unit
    // sphere, is t + R v); the scale direction (0, R^T t) completes J's columns to a basis.
    const detail::MotionTangent motion(Rm, tu);
    Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
    J.topLeftCorner<3, 3>().setIdentity();
    J.block<3, 2>(3, 3) = Rm.transpose() * motion.B;
    J.block<3, 1>(3, 5) = Rm.transpose() * tu;
    Eigen::Matrix<double, 6, 6> inner = Eigen::Matrix<double, 6, 6>::Zero();
    inner.topLeftCorner<5, 5>() = 0.5 * (tangent + tangent.transpose());
    inner(5, 5) = scaleStd * scaleStd;
    Eigen::Matrix<double, 6, 6> pose = J * inner * J.transpose();
    if (inverse) {
        // T^-1 Exp(-Ad_T xi) = (T Exp(xi))^-1, Ad_T = [R 0; [t]x R R].
        Eigen::Matrix<double, 6, 6> adjoint = Eigen::Matrix<double, 6, 6>::Zero();
        adjoint.topLeftCorner<3, 3>() = Rm;
        adjoint.bottomRightCorner<3, 3>() = Rm;
        adjoint.bottomLeftCorner<3, 3>() = detail::skew(tu) * Rm;
        pose = adjoint * pose * adjoint.transpose();
    }
    Mat out;
    eigen2cv(Eigen::Matrix<double, 6, 6>(0.5 * (pose + pose.transpose())), out);
    return out;
}

} // namespace rcme
} // namespace cv
