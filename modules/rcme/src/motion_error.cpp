// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Motion error metrics: the paper's dq and dt (Sec. V-B.1) and the angular errors.

#include "precomp.hpp"

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
Matrix3d readRotation(InputArray input, const char* name)
{
    const Mat m = input.getMat();
    if (m.empty() || m.dims != 2 || m.rows != 3 || m.cols != 3 || m.channels() != 1 ||
        !isFloatDepth(m.depth()))
        CV_Error(
            Error::StsBadArg,
            format("compareMotion: %s must be a 3x3 single-channel floating-point matrix", name));
    Mat md;
    m.convertTo(md, CV_64F);
    Matrix3d M;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            M(r, c) = md.at<double>(r, c);
    if (!M.allFinite())
        CV_Error(Error::StsBadArg, format("compareMotion: %s has non-finite entries", name));

    Eigen::JacobiSVD<Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Vector3d s = svd.singularValues();
    if ((s.array() - 1.0).abs().maxCoeff() > kRotationTolerance)
        CV_Error(Error::StsBadArg,
                 format("compareMotion: %s is not a rotation matrix (singular values %g, %g, %g)",
                        name, s(0), s(1), s(2)));
    const Matrix3d Q = svd.matrixU() * svd.matrixV().transpose();
    if (Q.determinant() < 0)
        CV_Error(Error::StsBadArg,
                 format("compareMotion: %s is not a rotation matrix (determinant < 0)", name));
    return Q;
}

// A non-zero 3-vector (3x1, 1x3, or 1x1 with three channels), returned with unit length.
Vector3d readDirection(InputArray input, const char* name)
{
    const Mat m = input.getMat();
    const bool shapeOk =
        !m.empty() && m.dims == 2 && isFloatDepth(m.depth()) &&
        ((m.channels() == 1 && ((m.rows == 3 && m.cols == 1) || (m.rows == 1 && m.cols == 3))) ||
         (m.channels() == 3 && m.rows == 1 && m.cols == 1));
    if (!shapeOk)
        CV_Error(Error::StsBadArg,
                 format("compareMotion: %s must be a floating-point 3-vector (3x1 or 1x3)", name));
    Mat md;
    m.reshape(1, 3).convertTo(md, CV_64F);
    const Vector3d v(md.at<double>(0), md.at<double>(1), md.at<double>(2));
    if (!v.allFinite())
        CV_Error(Error::StsBadArg, format("compareMotion: %s has non-finite entries", name));
    const double len = v.norm();
    if (!(len > 0))
        CV_Error(Error::StsBadArg, format("compareMotion: %s must have non-zero length", name));
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
    const Matrix3d Re = readRotation(R, "R");
    const Vector3d te = readDirection(t, "t");
    const Matrix3d Rg = readRotation(Rgt, "Rgt");
    const Vector3d tg = readDirection(tgt, "tgt");

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

} // namespace rcme
} // namespace cv
