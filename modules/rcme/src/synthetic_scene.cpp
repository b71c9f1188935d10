// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Synthetic two-view scenes with ground truth: the paper's corridor (Sec. V-B, Table I) and a
// well-conditioned generic scene. The construction is described in doc/synthetic.md.

#include "precomp.hpp"

namespace cv {
namespace rcme {

SceneParams::SceneParams()
    : kind(SCENE_CORRIDOR), numPoints(500), inlierRatio(0.5), sigma(1.0), seed(0),
      focalLength(500.0), imageWidth(640), imageHeight(480), baseline(1.0), corridorDepth(50.0),
      corridorWidth(4.0), corridorHeight(3.0), inlierRegion(1.0), planeRelief(0.0),
      forwardMotion(false)
{
}

SyntheticScene::SyntheticScene() {}

namespace {

using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

const int kMaxNumPoints = 10000000;
const double kDegToRad = CV_PI / 180.0;

// Corridor: largest rotation about each camera axis away from "looking down the corridor".
const double kCorridorMaxTiltDeg = 15.0;
// Corridor: camera centres stay at least this far from every wall (shrunk for thin corridors).
const double kCorridorMargin = 0.5;
// Corridor: camera 1 lies in the first 10% of the corridor length.
const double kCorridorEntranceFraction = 0.1;
// Generic scene: depth range of the points in front of camera 1, metres.
const double kGenericMinDepth = 4.0;
const double kGenericMaxDepth = 20.0;
// Generic scene: lateral jitter of the sideways baseline and rotation jitter of camera 2.
const double kGenericBaselineJitter = 0.3;
const double kGenericMaxTiltDeg = 6.0;
// Generic scene: camera 2 is redrawn while its rotation from camera 1 is smaller than this.
const double kGenericMinRotationDeg = 3.0;
// Plane scene: the plane n . X = d in camera 1's frame.
const Eigen::Vector3d kPlaneNormal = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
const double kPlaneDistance = 12.0;
// A point closer than this to a camera plane is treated as not in front of the camera.
const double kMinPointDepth = 1e-9;
// Attempts at placing the corridor camera centres before giving up.
const int kMaxCameraAttempts = 10000;
// A camera pair is redrawn while the two views share less than this fraction of the scene
// (narrow fields of view can otherwise point the cameras at disjoint parts of the corridor).
const double kMinSharedViewFraction = 0.01;
const int kSharedViewSamples = 1000;
const int kMaxCameraConfigurations = 100;

// A pinhole camera: x_cam = Rw (X_world - C).
struct Camera
{
    Matrix3d Rw;
    Vector3d C;
};

// splitmix64 of the seed: nearby seeds give unrelated cv::RNG states, and no seed maps to the
// zero state that cv::RNG silently replaces (which would make two seeds collide).
uint64 seedState(int seed)
{
    uint64 z = static_cast<uint64>(static_cast<int64>(seed)) + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z = z ^ (z >> 31);
    return z != 0 ? z : 0x9E3779B97F4A7C15ULL;
}

void requirePositiveFinite(double value, const char* field)
{
    if (!(std::isfinite(value) && value > 0))
        CV_Error(Error::StsBadArg,
                 format("SceneParams.%s must be finite and > 0 (got %g)", field, value));
}

void validate(const SceneParams& p)
{
    if (p.kind != SCENE_CORRIDOR && p.kind != SCENE_GENERIC && p.kind != SCENE_PLANE &&
        p.kind != SCENE_PURE_ROTATION)
        CV_Error(Error::StsBadArg,
                 format("SceneParams.kind must be SCENE_CORRIDOR, SCENE_GENERIC, SCENE_PLANE or "
                        "SCENE_PURE_ROTATION (got %d)",
                        static_cast<int>(p.kind)));
    if (p.numPoints < 1 || p.numPoints > kMaxNumPoints)
        CV_Error(Error::StsBadArg, format("SceneParams.numPoints must be in [1, %d] (got %d)",
                                          kMaxNumPoints, p.numPoints));
    if (!(p.inlierRatio >= 0.0 && p.inlierRatio <= 1.0))
        CV_Error(Error::StsBadArg,
                 format("SceneParams.inlierRatio must be in [0, 1] (got %g)", p.inlierRatio));
    if (!(std::isfinite(p.sigma) && p.sigma >= 0.0))
        CV_Error(Error::StsBadArg,
                 format("SceneParams.sigma must be finite and >= 0 (got %g)", p.sigma));
    requirePositiveFinite(p.focalLength, "focalLength");
    if (p.imageWidth <= 0)
        CV_Error(Error::StsBadArg,
                 format("SceneParams.imageWidth must be > 0 (got %d)", p.imageWidth));
    if (p.imageHeight <= 0)
        CV_Error(Error::StsBadArg,
                 format("SceneParams.imageHeight must be > 0 (got %d)", p.imageHeight));
    requirePositiveFinite(p.baseline, "baseline");
    // Checked for both kinds so that a parameter set is valid or not independently of kind.
    requirePositiveFinite(p.corridorDepth, "corridorDepth");
    requirePositiveFinite(p.corridorWidth, "corridorWidth");
    requirePositiveFinite(p.corridorHeight, "corridorHeight");
    if (!(p.inlierRegion > 0.0 && p.inlierRegion <= 1.0))
        CV_Error(Error::StsBadArg,
                 format("SceneParams.inlierRegion must be in (0, 1] (got %g)", p.inlierRegion));
    if (!(std::isfinite(p.planeRelief) && p.planeRelief >= 0.0))
        CV_Error(Error::StsBadArg,
                 format("SceneParams.planeRelief must be finite and >= 0 (got %g)", p.planeRelief));
}

const char* kindName(SceneKind kind)
{
    switch (kind) {
    case SCENE_CORRIDOR:
        return "SCENE_CORRIDOR";
    case SCENE_GENERIC:
        return "SCENE_GENERIC";
    case SCENE_PLANE:
        return "SCENE_PLANE";
    case SCENE_PURE_ROTATION:
        return "SCENE_PURE_ROTATION";
    }
    return "?";
}

std::string describe(const SceneParams& p)
{
    return format("kind=%s, corridor %gx%gx%g m (WxHxD), baseline=%g m, f=%g px, image %dx%d, "
                  "inlierRegion=%g",
                  kindName(p.kind), p.corridorWidth, p.corridorHeight, p.corridorDepth, p.baseline,
                  p.focalLength, p.imageWidth, p.imageHeight, p.inlierRegion);
}

// Camera-to-world rotation of a camera looking along +Z, turned by random yaw (about Y), pitch
// (about X) and roll (about Z), each uniform in [-maxDeg, maxDeg]. The draws are separate
// statements so that their order does not depend on the compiler.
Matrix3d randomTilt(RNG& rng, double maxDeg)
{
    const double maxRad = maxDeg * kDegToRad;
    const double yaw = rng.uniform(-maxRad, maxRad);
    const double pitch = rng.uniform(-maxRad, maxRad);
    const double roll = rng.uniform(-maxRad, maxRad);
    return (Eigen::AngleAxisd(yaw, Vector3d::UnitY()) *
            Eigen::AngleAxisd(pitch, Vector3d::UnitX()) *
            Eigen::AngleAxisd(roll, Vector3d::UnitZ()))
        .toRotationMatrix();
}

// Uniform direction on the unit sphere.
Vector3d randomDirection(RNG& rng)
{
    const double z = rng.uniform(-1.0, 1.0);
    const double phi = rng.uniform(0.0, 2.0 * CV_PI);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vector3d(r * std::cos(phi), r * std::sin(phi), z);
}

// Corridor of the paper: X in [-W/2, W/2], Y in [-H/2, H/2] (Y points down, as in the camera
// frame, so the floor is Y = +H/2), Z from the open entrance at 0 to the far wall at D.
struct Corridor
{
    double W, H, D;

    // Uniform on the five walls: a wall is chosen with probability proportional to its area.
    Vector3d sample(RNG& rng) const
    {
        const double areas[5] = {H * D, H * D, W * D, W * D, W * H};
        const double total = areas[0] + areas[1] + areas[2] + areas[3] + areas[4];
        double pick = rng.uniform(0.0, total);
        int wall = 0;
        while (wall < 4 && pick >= areas[wall]) {
            pick -= areas[wall];
            ++wall;
        }
        const double a = rng.uniform(0.0, 1.0);
        const double b = rng.uniform(0.0, 1.0);
        switch (wall) {
        case 0: // left
            return Vector3d(-0.5 * W, (a - 0.5) * H, b * D);
        case 1: // right
            return Vector3d(0.5 * W, (a - 0.5) * H, b * D);
        case 2: // floor
            return Vector3d((a - 0.5) * W, 0.5 * H, b * D);
        case 3: // ceiling
            return Vector3d((a - 0.5) * W, -0.5 * H, b * D);
        default: // far end
            return Vector3d((a - 0.5) * W, (b - 0.5) * H, D);
        }
    }
};

void placeCorridorCameras(const SceneParams& p, RNG& rng, Camera& cam1, Camera& cam2)
{
    const double W = p.corridorWidth, H = p.corridorHeight, D = p.corridorDepth;
    // Thin corridors keep a non-empty region for the camera centres.
    const double m = std::min(kCorridorMargin, 0.25 * std::min(W, std::min(H, D)));
    const Vector3d lo(-0.5 * W + m, -0.5 * H + m, m);
    const Vector3d hi(0.5 * W - m, 0.5 * H - m, D - m);
    if (p.baseline >= (hi - lo).norm())
        CV_Error(Error::StsBadArg,
                 format("SceneParams.baseline (%g m) does not fit inside the corridor with a %g m "
                        "margin (%s)",
                        p.baseline, m, describe(p).c_str()));
    const double entranceEnd = m + kCorridorEntranceFraction * (hi.z() - lo.z());

    bool placed = false;
    for (int attempt = 0; attempt < kMaxCameraAttempts && !placed; ++attempt) {
        const double x = rng.uniform(lo.x(), hi.x());
        const double y = rng.uniform(lo.y(), hi.y());
        const double z = rng.uniform(lo.z(), entranceEnd);
        cam1.C = Vector3d(x, y, z);
        cam2.C = cam1.C + p.baseline * randomDirection(rng);
        placed = (cam2.C.array() >= lo.array()).all() && (cam2.C.array() <= hi.array()).all();
    }
    if (!placed)
        CV_Error(Error::StsError,
                 format("generateScene: could not place two cameras %g m apart inside the "
                        "corridor (%s)",
                        p.baseline, describe(p).c_str()));
    cam1.Rw = randomTilt(rng, kCorridorMaxTiltDeg).transpose();
    cam2.Rw = randomTilt(rng, kCorridorMaxTiltDeg).transpose();
}

// Generic scene: the world frame is camera 1's. Camera 2 moves mostly along +-X and looks at
// the middle of the point cloud, with a small random tilt on top.
void placeGenericCameras(const SceneParams& p, RNG& rng, Camera& cam1, Camera& cam2)
{
    cam1.Rw.setIdentity();
    cam1.C.setZero();

    const double side = rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    const double dy = rng.uniform(-kGenericBaselineJitter, kGenericBaselineJitter);
    const double dz = rng.uniform(-kGenericBaselineJitter, kGenericBaselineJitter);
    // The same draws either way, so a seed gives the same jitter and tilt to both motions.
    cam2.C = p.baseline *
             (p.forwardMotion ? Vector3d(side * dy, dz, 1.0) : Vector3d(side, dy, dz)).normalized();

    const Vector3d target(0.0, 0.0, 0.5 * (kGenericMinDepth + kGenericMaxDepth));
    const Vector3d zAxis = (target - cam2.C).normalized();
    // Y (down) of camera 1 fixes the roll of the look-at frame; it is never parallel to zAxis
    // because the target is straight ahead of camera 1 and the baseline is mostly sideways.
    const Vector3d xAxis = Vector3d::UnitY().cross(zAxis).normalized();
    const Vector3d yAxis = zAxis.cross(xAxis);
    Matrix3d lookAt;
    lookAt.col(0) = xAxis;
    lookAt.col(1) = yAxis;
    lookAt.col(2) = zAxis;
    // The tilt may cancel the convergence of the look-at frame; a few degrees of rotation keep
    // the rotation part of the estimate exercised. Bounded redraws: with a large baseline the
    // look-at rotation alone exceeds the minimum.
    for (int attempt = 0; attempt < 100; ++attempt) {
        cam2.Rw = (lookAt * randomTilt(rng, kGenericMaxTiltDeg)).transpose();
        const double cosAngle = 0.5 * (cam2.Rw.trace() - 1.0);
        if (cosAngle <= std::cos(kGenericMinRotationDeg * kDegToRad))
            break;
    }
}

struct Intrinsics
{
    double f, cx, cy;
    int width, height;

    // Noise-free projection; false when the point is not strictly in front of the camera.
    bool project(const Camera& cam, const Vector3d& X, Vector2d& uv) const
    {
        const Vector3d Xc = cam.Rw * (X - cam.C);
        if (!(Xc.z() > kMinPointDepth))
            return false;
        uv = Vector2d(f * Xc.x() / Xc.z() + cx, f * Xc.y() / Xc.z() + cy);
        return true;
    }

    bool inside(const Vector2d& uv) const
    {
        return uv.x() >= 0.0 && uv.x() < width && uv.y() >= 0.0 && uv.y() < height;
    }
};

// Where scene points come from: the corridor walls, or the generic scene's volume.
struct ScenePoints
{
    SceneKind kind;
    Intrinsics K;
    Corridor corridor;
    double planeRelief;

    Vector3d sample(RNG& rng) const
    {
        if (kind == SCENE_CORRIDOR)
            return corridor.sample(rng);
        // Uniform in camera 1's image and in depth: every point is in view of camera 1, whose
        // frame is the world frame of the generic scene.
        const double u = rng.uniform(0.0, static_cast<double>(K.width));
        const double v = rng.uniform(0.0, static_cast<double>(K.height));
        const double z = rng.uniform(kGenericMinDepth, kGenericMaxDepth);
        const Vector3d ray((u - K.cx) / K.f, (v - K.cy) / K.f, 1.0);
        if (kind != SCENE_PLANE)
            return ray * z;
        const Vector3d onPlane = ray * (kPlaneDistance / kPlaneNormal.dot(ray)); // the same ray
        if (planeRelief <= 0) // no draw: the plane's scenes stay those of before the relief
            return onPlane;
        return onPlane + rng.uniform(-planeRelief, planeRelief) * kPlaneNormal;
    }
};

// Fraction of scene points (noise-free) that both cameras see; cheap with a fixed sample size.
double sharedViewFraction(const ScenePoints& scene, const Camera& cam1, const Camera& cam2,
                          RNG& rng)
{
    int seen = 0;
    for (int i = 0; i < kSharedViewSamples; ++i) {
        const Vector3d X = scene.sample(rng);
        Vector2d uv1, uv2;
        seen += scene.K.project(cam1, X, uv1) && scene.K.project(cam2, X, uv2) &&
                scene.K.inside(uv1) && scene.K.inside(uv2);
    }
    return static_cast<double>(seen) / kSharedViewSamples;
}

Mat toMat(const Matrix3d& M)
{
    Mat out(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            out.at<double>(r, c) = M(r, c);
    return out;
}

} // namespace

SyntheticScene generateScene(const SceneParams& params)
{
    validate(params);
    RNG rng(seedState(params.seed));

    const int n = params.numPoints;
    // Round half up, independently of the floating-point rounding mode.
    const int numInliers = std::min(n, static_cast<int>(std::floor(n * params.inlierRatio + 0.5)));

    const Intrinsics K{params.focalLength, 0.5 * params.imageWidth, 0.5 * params.imageHeight,
                       params.imageWidth, params.imageHeight};
    const ScenePoints scenePoints{
        params.kind, K, Corridor{params.corridorWidth, params.corridorHeight, params.corridorDepth},
        params.planeRelief};
    const Vector2d inlierCorner(params.inlierRegion * params.imageWidth,
                                params.inlierRegion * params.imageHeight);

    // The cameras are drawn before anything that depends on numPoints, inlierRatio or sigma, so
    // a seed gives the same motion whatever those are.
    Camera cam1, cam2;
    bool overlapping = false;
    for (int config = 0; config < kMaxCameraConfigurations && !overlapping; ++config) {
        if (params.kind == SCENE_CORRIDOR)
            placeCorridorCameras(params, rng, cam1, cam2);
        else
            placeGenericCameras(params, rng, cam1, cam2);
        if (params.kind == SCENE_PURE_ROTATION) {
            // Camera 2 at camera 1's centre, rotated by 3-6 deg: no translation at all.
            cam2.C = cam1.C;
            for (int attempt = 0; attempt < 100; ++attempt) {
                cam2.Rw = randomTilt(rng, kGenericMaxTiltDeg).transpose();
                if (0.5 * (cam2.Rw.trace() - 1.0) <= std::cos(kGenericMinRotationDeg * kDegToRad))
                    break;
            }
        }
        overlapping = sharedViewFraction(scenePoints, cam1, cam2, rng) >= kMinSharedViewFraction;
    }
    if (!overlapping)
        CV_Error(Error::StsError,
                 format("generateScene: no camera pair out of %d sees at least %g%% of the sampled "
                        "scene points in both images (%s)",
                        kMaxCameraConfigurations, 100.0 * kMinSharedViewFraction,
                        describe(params).c_str()));

    std::vector<Vector2d> pts1(n), pts2(n);
    std::vector<uchar> isInlier(n, 0);

    // Rejection sampling. The cameras share at least kMinSharedViewFraction of the scene, so the
    // bound is far above the expected number of attempts; it only guards against endless loops.
    const int64 maxAttempts = std::max<int64>(100000, 1000 * static_cast<int64>(numInliers));
    int64 attempts = 0;
    int count = 0;
    while (count < numInliers) {
        if (attempts >= maxAttempts)
            CV_Error(Error::StsError,
                     format("generateScene: only %d of %d inliers are visible in both images "
                            "after %lld attempts (%s)",
                            count, numInliers, static_cast<long long>(attempts),
                            describe(params).c_str()));
        ++attempts;

        const Vector3d X = scenePoints.sample(rng);
        Vector2d uv1, uv2;
        if (!K.project(cam1, X, uv1) || !K.project(cam2, X, uv2))
            continue;
        // Drawn even for sigma = 0: a seed then gives the same scene points for every sigma,
        // except for the few that the noise pushes out of an image.
        const double e1x = rng.gaussian(params.sigma);
        const double e1y = rng.gaussian(params.sigma);
        const double e2x = rng.gaussian(params.sigma);
        const double e2y = rng.gaussian(params.sigma);
        uv1 += Vector2d(e1x, e1y);
        uv2 += Vector2d(e2x, e2y);
        // Tested after the noise so that every reported pixel lies inside its image.
        if (!K.inside(uv1) || !K.inside(uv2) || uv1.x() >= inlierCorner.x() ||
            uv1.y() >= inlierCorner.y())
            continue;
        pts1[count] = uv1;
        pts2[count] = uv2;
        isInlier[count] = 1;
        ++count;
    }

    for (int i = numInliers; i < n; ++i) {
        const double u1 = rng.uniform(0.0, static_cast<double>(params.imageWidth));
        const double v1 = rng.uniform(0.0, static_cast<double>(params.imageHeight));
        const double u2 = rng.uniform(0.0, static_cast<double>(params.imageWidth));
        const double v2 = rng.uniform(0.0, static_cast<double>(params.imageHeight));
        pts1[i] = Vector2d(u1, v1);
        pts2[i] = Vector2d(u2, v2);
    }

    // Fisher-Yates with cv::RNG: std::shuffle's algorithm is implementation-defined, so it would
    // break reproducibility across standard libraries.
    for (int i = n - 1; i > 0; --i) {
        const int j = rng.uniform(0, i + 1);
        std::swap(pts1[i], pts1[j]);
        std::swap(pts2[i], pts2[j]);
        std::swap(isInlier[i], isInlier[j]);
    }

    SyntheticScene scene;
    scene.points1.create(n, 2, CV_64F);
    scene.points2.create(n, 2, CV_64F);
    scene.inlierMask.create(n, 1, CV_8U);
    for (int i = 0; i < n; ++i) {
        double* p1 = scene.points1.ptr<double>(i);
        double* p2 = scene.points2.ptr<double>(i);
        p1[0] = pts1[i].x();
        p1[1] = pts1[i].y();
        p2[0] = pts2[i].x();
        p2[1] = pts2[i].y();
        scene.inlierMask.at<uchar>(i) = isInlier[i];
    }

    // x2 = R x1 + t with x_i = Rw_i (X - C_i): R = Rw2 Rw1^T, t = Rw2 (C1 - C2), |t| = baseline.
    const Matrix3d R = cam2.Rw * cam1.Rw.transpose();
    // A pure rotation has no translation: t, E and F are zero.
    const Vector3d t = params.kind == SCENE_PURE_ROTATION
                           ? Vector3d::Zero()
                           : Vector3d((cam2.Rw * (cam1.C - cam2.C)).normalized());
    Matrix3d tx;
    tx << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
    const Matrix3d E = tx * R;

    Matrix3d Kmat;
    Kmat << K.f, 0.0, K.cx, 0.0, K.f, K.cy, 0.0, 0.0, 1.0;
    const Matrix3d Kinv = Kmat.inverse();
    Matrix3d F = Kinv.transpose() * E * Kinv;
    if (F.norm() > 0)
        F /= F.norm();
    // F is defined up to sign: make the entry of largest magnitude (first in row-major order on
    // ties) positive so that the ground truth is unique.
    int bestR = 0, bestC = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (std::abs(F(r, c)) > std::abs(F(bestR, bestC))) {
                bestR = r;
                bestC = c;
            }
    if (F(bestR, bestC) < 0)
        F = -F;

    scene.cameraMatrix = toMat(Kmat);
    scene.R = toMat(R);
    scene.t = Mat(Vec3d(t.x(), t.y(), t.z()));
    scene.E = toMat(E);
    scene.F = toMat(F);
    return scene;
}

} // namespace rcme
} // namespace cv
