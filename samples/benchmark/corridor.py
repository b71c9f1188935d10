"""The paper's Table I setting: the corridor scenes of doc/synthetic.md with ground truth."""
import numpy as np

from methods import rcme
from pairs import Pair

SCENE_FIELDS = ["numPoints", "focalLength", "imageWidth", "imageHeight", "baseline",
                "corridorDepth", "corridorWidth", "corridorHeight"]


def scene_params(points, inlier_ratio, sigma, seed):
    params = rcme.SceneParams()
    params.kind = rcme.SCENE_CORRIDOR
    params.numPoints, params.inlierRatio, params.sigma, params.seed = (points, inlier_ratio,
                                                                       sigma, seed)
    return params


def describe_scene(points):
    """The fixed scene parameters, for the report."""
    params = scene_params(points, 0.5, 1.0, 0)
    return ", ".join("%s %g" % (name, getattr(params, name)) for name in SCENE_FIELDS)


def corridor_pair(points, inlier_ratio, sigma, seed):
    scene = rcme.generateScene(scene_params(points, inlier_ratio, sigma, seed))
    label = "corridor w=%.1f sigma=%.1f" % (inlier_ratio, sigma)
    return Pair(label, "%s seed %d" % (label, seed), np.asarray(scene.points1),
                np.asarray(scene.points2), np.asarray(scene.cameraMatrix), np.asarray(scene.R),
                np.asarray(scene.t).reshape(3), labels=np.asarray(scene.inlierMask).ravel() > 0,
                sigma=sigma)
