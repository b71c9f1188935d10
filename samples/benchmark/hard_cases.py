"""The hard-case suite (issue 15): synthetic scenes with ground truth on which wrong answers are
plentiful, deterministic per seed. The corridor and generic scenes come from rcme.generateScene
with harder settings; planes and pure rotations (which that generator does not make) are built
here with numpy's generator seeded by the scene's seed."""
import numpy as np

from corridor import scene_params
from methods import rcme
from pairs import Pair

IMAGE_W, IMAGE_H, FOCAL = 640, 480, 500.0
K_DEFAULT = np.array([[FOCAL, 0, IMAGE_W / 2], [0, FOCAL, IMAGE_H / 2], [0, 0, 1.0]])


def _generated(label, seed, sigma, **fields):
    params = scene_params(500, 0.5, sigma, seed)
    for name, value in fields.items():
        setattr(params, name, value)
    scene = rcme.generateScene(params)
    return Pair("hard: " + label, "%s seed %d" % (label, seed), np.asarray(scene.points1),
                np.asarray(scene.points2), np.asarray(scene.cameraMatrix), np.asarray(scene.R),
                np.asarray(scene.t).reshape(3), labels=np.asarray(scene.inlierMask).ravel() > 0,
                sigma=sigma)


def _rotation(rng, max_deg):
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angle = np.radians(rng.uniform(0.5 * max_deg, max_deg))
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _two_views(label, seed, kind, points=500, inlier_ratio=0.5, sigma=1.0):
    """A plane (tilted, 8 m away, 1 m of sideways baseline) or a pure rotation (points 4-20 m
    away), half outliers, K_DEFAULT. Pure rotation: t_gt is zero, so any motion is wrong."""
    rng = np.random.default_rng(seed)
    R = _rotation(rng, 10.0)
    t = np.array([1.0, rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)]) if kind == "plane" \
        else np.zeros(3)
    normal = np.array([0.1, -0.2, 1.0]) / np.linalg.norm([0.1, -0.2, 1.0])
    Kinv = np.linalg.inv(K_DEFAULT)
    n_in = int(round(points * inlier_ratio))
    p1, p2 = [], []
    while len(p1) < n_in:
        ray = Kinv @ np.array([rng.uniform(0, IMAGE_W), rng.uniform(0, IMAGE_H), 1.0])
        depth = 8.0 / ray.dot(normal) if kind == "plane" else rng.uniform(4.0, 20.0)
        X2 = R @ (ray * depth) + t
        if X2[2] <= 0:
            continue
        x2 = K_DEFAULT @ X2
        q = x2[:2] / x2[2] + rng.normal(0, sigma, 2)
        if not (0 <= q[0] < IMAGE_W and 0 <= q[1] < IMAGE_H):
            continue
        p1.append((K_DEFAULT @ ray)[:2] + rng.normal(0, sigma, 2))
        p2.append(q)
    outliers = points - n_in
    p1 = np.vstack([np.array(p1).reshape(-1, 2),
                    rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (outliers, 2))])
    p2 = np.vstack([np.array(p2).reshape(-1, 2),
                    rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (outliers, 2))])
    labels = np.arange(points) < n_in
    return Pair("hard: " + label, "%s seed %d" % (label, seed), p1, p2, K_DEFAULT, R, t,
                labels=labels, sigma=sigma)


def _all_outliers(seed, points=300):
    """No true correspondence: every returned motion is wrong (t_gt zero, no_motion)."""
    rng = np.random.default_rng(seed)
    p1 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (points, 2))
    p2 = rng.uniform([0, 0], [IMAGE_W, IMAGE_H], (points, 2))
    return Pair("hard: all outliers", "all outliers seed %d" % seed, p1, p2, K_DEFAULT,
                np.eye(3), np.zeros(3), labels=np.zeros(points, bool), sigma=1.0)


def hard_case_pairs(seeds):
    """Every case of the suite for seeds 0..seeds-1."""
    pairs = []
    for seed in range(seeds):
        pairs += [
            _generated("corridor w=0.3", seed, 1.0, inlierRatio=0.3),
            _generated("narrow corridor", seed, 1.0, corridorWidth=1.5, corridorHeight=1.5),
            # a small object far away through a narrow field of view: bas-relief ambiguity
            _generated("narrow field of view", seed, 1.0, kind=rcme.SCENE_GENERIC,
                       focalLength=2000.0, baseline=0.3),
            _generated("few points (40)", seed, 1.0, kind=rcme.SCENE_GENERIC, numPoints=40),
            _generated("noise 2.5 px", seed, 2.5, kind=rcme.SCENE_GENERIC),
            _two_views("plane", seed, "plane"),
            _two_views("pure rotation", seed, "pure rotation"),
            _all_outliers(seed),
        ]
    return pairs
