"""The hard-case suite (issue 15): synthetic scenes with ground truth on which wrong answers are
plentiful, deterministic per seed: rcme.generateScene (the C++ generator, so C++ and Python see
the same scenes) with harder settings, and all-outlier input drawn with numpy's generator
seeded by the scene's seed."""
import numpy as np
import cv2

from corridor import scene_params
from methods import rcme
from pairs import Pair

IMAGE_W, IMAGE_H, FOCAL = 640, 480, 500.0
K_DEFAULT = np.array([[FOCAL, 0, IMAGE_W / 2], [0, FOCAL, IMAGE_H / 2], [0, 0, 1.0]])


def _generated(label, seed, sigma, iterations=None, **fields):
    """A generated scene with its ground truth; iterations: the case's own N, else the run's."""
    params = scene_params(500, 0.5, sigma, seed)
    for name, value in fields.items():
        setattr(params, name, value)
    scene = rcme.generateScene(params)
    return Pair("hard: " + label, "%s seed %d" % (label, seed), np.asarray(scene.points1),
                np.asarray(scene.points2), np.asarray(scene.cameraMatrix), np.asarray(scene.R),
                np.asarray(scene.t).reshape(3), labels=np.asarray(scene.inlierMask).ravel() > 0,
                sigma=sigma, iterations=iterations)


def _all_outliers(seed, points=300):
    """No true correspondence: every returned motion is wrong (t_gt zero, no_motion)."""
    rng = np.random.default_rng(seed)
    p1 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (points, 2))
    p2 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (points, 2))
    return Pair("hard: all outliers", "all outliers seed %d" % seed, p1, p2, K_DEFAULT,
                np.eye(3), np.zeros(3), labels=np.zeros(points, bool), sigma=1.0)


def _normalized_with_gross_outliers(seed, points=60):
    """Points in normalized coordinates (K = I, the noise and the threshold in those units), as
    many VO programs pass them: a generic scene's true matches with three gross outliers, one
    far off every image ((0, 0) to (1000, 1000)) and two mismatches inside the view."""
    params = scene_params(points, 1.0, 1.0, seed)
    params.kind = rcme.SCENE_GENERIC
    scene = rcme.generateScene(params)
    K = np.asarray(scene.cameraMatrix)
    centre, focal = K[:2, 2], K[0, 0]
    p1 = (np.asarray(scene.points1) - centre) / focal
    p2 = (np.asarray(scene.points2) - centre) / focal
    rng = np.random.default_rng(seed)
    half = np.array([IMAGE_W, IMAGE_H]) / (2 * focal)
    inside1 = rng.uniform(-half, half, (2, 2))
    inside2 = rng.uniform(-half, half, (2, 2))
    p1 = np.vstack([p1, [[0.0, 0.0]], inside1])
    p2 = np.vstack([p2, [[1000.0, 1000.0]], inside2])
    labels = np.concatenate([np.asarray(scene.inlierMask).ravel() > 0, np.zeros(3, bool)])
    return Pair("hard: normalized coordinates", "normalized K = I seed %d" % seed, p1, p2,
                np.eye(3), np.asarray(scene.R), np.asarray(scene.t).reshape(3), labels=labels,
                sigma=1.0 / focal)


def hard_case_pairs(seeds, first=0):
    """Every case of the suite for seeds first..first+seeds-1 (the benchmark's start at 0)."""
    pairs = []
    for seed in range(first, first + seeds):
        pairs += [
            # the "corridor at inlier ratio 0.3 and N = 200": 200 hypotheses for everyone
            _generated("corridor w=0.3, N = 200", seed, 1.0, iterations=200, inlierRatio=0.3),
            _generated("narrow corridor", seed, 1.0, corridorWidth=1.5, corridorHeight=1.5),
            # a small object far away through a narrow field of view: bas-relief ambiguity
            _generated("narrow field of view", seed, 1.0, kind=rcme.SCENE_GENERIC,
                       focalLength=2000.0, baseline=0.3),
            _generated("few points (40)", seed, 1.0, kind=rcme.SCENE_GENERIC, numPoints=40),
            _generated("noise 2.5 px", seed, 2.5, kind=rcme.SCENE_GENERIC),
            _generated("plane", seed, 1.0, kind=rcme.SCENE_PLANE),
            # points within 0.5 m of a plane 12 m away: about 2 px of parallax off the plane
            _generated("near-planar", seed, 1.0, kind=rcme.SCENE_PLANE, planeRelief=0.5),
            _generated("forward motion", seed, 1.0, kind=rcme.SCENE_GENERIC, forwardMotion=True),
            # the inliers in the top-left quadrant of image 1, the outliers everywhere
            _generated("one quadrant", seed, 1.0, kind=rcme.SCENE_GENERIC, inlierRegion=0.5),
            # t_gt is zero: no returned motion is right
            _generated("pure rotation", seed, 1.0, kind=rcme.SCENE_PURE_ROTATION),
            _all_outliers(seed),
            # issue 34: K = I with a gross outlier far off the image
            _normalized_with_gross_outliers(seed),
        ]
    return pairs


# The F-only hard cases (issue 38): no camera matrix for anyone. Each scene is judged by
# F_JUDGE_POINTS noise-free correspondences spread over the whole of image 1 at the depths of the
# scene's true points (5th to 95th percentile; a plane's: from half its nearest to one and a half
# times its farthest, as a plane spans few depths), so that an F right only where the matches are
# (a cluster, a plane) is wrong.
F_JUDGE_POINTS = 200


def _depths(K, R, t, p1, p2):
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    X = cv2.triangulatePoints(P1, P2, p1.T, p2.T)
    return X[2] / X[3]


def _project(K, R, t, x1, depth):
    X = (np.linalg.inv(K) @ np.vstack([x1.T, np.ones(len(x1))])) * depth
    x2 = K @ (R @ X + t.reshape(3, 1))
    return (x2[:2] / x2[2]).T


def _judge_points(K, R, t, p1, p2, rng, plane):
    depth = _depths(K, R, t, p1, p2)
    near, far = np.percentile(depth[depth > 0], [5, 95])
    if plane:
        near, far = 0.5 * depth.min(), 1.5 * depth.max()
    x1 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (F_JUDGE_POINTS, 2))
    x2 = _project(K, R, t, x1, rng.uniform(near, far, F_JUDGE_POINTS))
    return np.hstack([x1, x2])


def _f_only(label, seed, points1, points2, truth, K, R, t, plane=False):
    rng = np.random.default_rng(1000 + seed)
    judge = _judge_points(K, R, t, points1[truth], points2[truth], rng, plane)
    return Pair("F-only hard: " + label, "%s seed %d" % (label, seed), points1, points2,
                labels=truth, gt_points=judge, sigma=1.0)


def _f_only_generated(label, seed, **fields):
    params = scene_params(500, 0.5, 1.0, seed)
    params.kind = rcme.SCENE_GENERIC
    for name, value in fields.items():
        setattr(params, name, value)
    scene = rcme.generateScene(params)
    return _f_only(label, seed, np.asarray(scene.points1), np.asarray(scene.points2),
                   np.asarray(scene.inlierMask).ravel() > 0, np.asarray(scene.cameraMatrix),
                   np.asarray(scene.R), np.asarray(scene.t).reshape(3))


def _plane_with_off_plane_points(seed, off_plane):
    """A plane's 300 correspondences (half true) plus `off_plane` true matches off it, at
    depths from half the plane's nearest to one and a half times its farthest."""
    params = scene_params(300, 0.5, 1.0, seed)
    params.kind = rcme.SCENE_PLANE
    scene = rcme.generateScene(params)
    K, R = np.asarray(scene.cameraMatrix), np.asarray(scene.R)
    t = np.asarray(scene.t).reshape(3)
    p1, p2 = np.asarray(scene.points1), np.asarray(scene.points2)
    truth = np.asarray(scene.inlierMask).ravel() > 0
    depth = _depths(K, R, t, p1[truth], p2[truth])  # the plane's, before the points off it
    rng = np.random.default_rng(2000 + seed)
    x1 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (off_plane, 2))
    x2 = _project(K, R, t, x1, rng.uniform(0.5 * depth.min(), 1.5 * depth.max(), off_plane))
    x1 = x1 + rng.normal(0, 1.0, x1.shape)
    x2 = x2 + rng.normal(0, 1.0, x2.shape)
    label = "plane + %d off-plane points" % off_plane if off_plane else "plane"
    return _f_only(label, seed, np.vstack([p1, x1]),
                   np.vstack([p2, x2]), np.concatenate([truth, np.ones(off_plane, bool)]),
                   K, R, t, plane=True)


def f_only_hard_case_pairs(seeds, first=0):
    """Every F-only hard case for seeds first..first+seeds-1 (generic scenes unless named)."""
    pairs = []
    for seed in range(first, first + seeds):
        pairs += [_f_only_generated("%d %% true of 500" % (100 * w), seed, inlierRatio=w)
                  for w in (0.10, 0.15, 0.25)]
        pairs += [_f_only_generated("%d points" % n, seed, numPoints=n) for n in (40, 60, 80)]
        pairs += [_plane_with_off_plane_points(seed, k) for k in (0, 5, 20)]
        # the true matches in the top-left 30 % x 30 % of image 1, the outliers everywhere
        pairs += [_f_only_generated("clustered matches", seed, inlierRegion=0.3)]
    return pairs
