"""The compared estimators behind one call signature, so every method sees the same
correspondences, the same pixel threshold, the same iteration budget N and the same seed.

run(method, p1, p2, K, budget) -> Estimate with F (pixels), R and t (x2 = R x1 + t, |t| = 1,
only with K), the inlier mask, whether a model came out, and the wall time of the call."""
import time
from dataclasses import dataclass

import numpy as np
import cv2

import metrics

try:
    import rcme
except ImportError:  # built inside OpenCV
    rcme = cv2.rcme
try:  # a peer, only in the venv of with_poselib.sh: never a dependency of the module
    import poselib
except ImportError:
    poselib = None

CHI2_1_95 = 3.841458820694124  # chi2_1^-1(0.95): threshold = sigma * sqrt(.) = 1.96 sigma
# Confidence ~1 keeps OpenCV's adaptive iteration bound at maxIters.
OPENCV_CONFIDENCE = 1.0 - 1e-12
# Both libraries' default confidence, for the runs that may stop early (Budget.adaptive).
DEFAULT_CONFIDENCE = 0.99


@dataclass
class Budget:
    """iterations: N, exactly (the paper's experiments); with adaptive, at most N, each library
    stopping by its own adaptive bound at DEFAULT_CONFIDENCE (how they run by default)."""
    iterations: int
    sigma: float
    seed: int
    adaptive: bool = False

    @property
    def threshold(self):
        return self.sigma * np.sqrt(CHI2_1_95)

    @property
    def opencv_confidence(self):
        return DEFAULT_CONFIDENCE if self.adaptive else OPENCV_CONFIDENCE


# Estimate.status of a run without a model: rcme declined (PQI), rcme found the inliers
# degenerate (a homography explains them about as well as F), a pure rotation, a motion the
# inliers do not determine (undetermined), or no model for another reason (OpenCV returned
# none, too few points).
PQI, DEGENERATE, NO_MODEL = "PQI", "degenerate", "no model"
PURE_ROTATION = "pure rotation"
RCME_OUTCOMES = {int(rcme.STATUS_POOR_QUALITY_INPUT): PQI,
                 int(rcme.STATUS_DEGENERATE_CONFIGURATION): DEGENERATE}
UNDETERMINED = "undetermined"
RCME_OUTCOMES[int(rcme.STATUS_PURE_ROTATION)] = PURE_ROTATION
RCME_OUTCOMES[int(rcme.STATUS_UNDETERMINED_MOTION)] = UNDETERMINED


@dataclass
class Estimate:
    ok: bool
    status: str  # "ok" or one of the statuses above
    F: object = None
    R: object = None
    t: object = None
    mask: object = None
    seconds: float = 0.0
    # A status that says "do not trust a motion" (rcme's non-success statuses); OpenCV's
    # estimators have none: a run of theirs without a model is NO_MODEL, not flagged.
    flagged: bool = False
    # rcme's Report.rejectedF/R/t when flagged: the model turned down, judged to tell a caught
    # failure from a false alarm (None when there was none).
    rejected_F: object = None
    rejected_R: object = None
    rejected_t: object = None


# The library's defaults as a user gets them (rcme.Params()), a row of its own.
DEFAULT_METHOD = "rcme default"


def rcme_params(method, budget):
    """The paper's configuration of method (Params.asPublished), or the library's defaults for
    method None; either way with the budget's noise, threshold, N and seed."""
    if method is None:
        params = rcme.Params()
    else:
        as_published = getattr(rcme.Params, "asPublished", None) or rcme.Params_asPublished
        params = as_published(method)
    params.sigma = budget.sigma
    params.threshold = budget.threshold
    params.maxIterations = budget.iterations
    params.exactIterations = not budget.adaptive
    params.confidence = DEFAULT_CONFIDENCE
    params.randomGeneratorState = budget.seed
    return params


def motion_from_essential(E, K, p1, p2, mask=None):
    """cv2.recoverPose on the given inliers (all points without a mask): R, t or None."""
    if mask is not None:
        keep = mask.ravel() > 0
        p1, p2 = p1[keep], p2[keep]
    if len(p1) < 5:
        return None, None
    _, R, t, _ = cv2.recoverPose(E, p1, p2, K)
    return R, t


def motion_from_f(F, K, p1, p2, mask=None):
    """E = K^T F K, then cv2.recoverPose: how an uncalibrated F becomes a motion."""
    return motion_from_essential(K.T @ F @ K, K, p1, p2, mask)


def _normalized(F):
    return F / np.linalg.norm(F)


def _run_rcme(method, **fields):
    def run(p1, p2, K, budget):
        params = rcme_params(method, budget)
        for name, value in fields.items():
            setattr(params, name, value)
        start = time.perf_counter()
        report = rcme.estimateRelativeMotion(p1, p2, K if K is not None else np.zeros((0, 0)),
                                             params)
        seconds = time.perf_counter() - start
        ok = report.status == rcme.STATUS_SUCCESS
        estimate = Estimate(ok, "ok" if ok else RCME_OUTCOMES.get(int(report.status), NO_MODEL),
                            mask=np.asarray(report.mask).ravel().astype(bool), seconds=seconds)
        if ok:
            estimate.F = _normalized(np.asarray(report.F))
            if K is not None:
                estimate.R, estimate.t = np.asarray(report.R), np.asarray(report.t).reshape(3, 1)
            return estimate
        estimate.flagged = True
        if report.rejectedF is not None:
            estimate.rejected_F = _normalized(np.asarray(report.rejectedF))
        if K is not None and report.rejectedR is not None:
            estimate.rejected_R = np.asarray(report.rejectedR)
            estimate.rejected_t = np.asarray(report.rejectedT).reshape(3, 1)
        return estimate
    return run


def default_runner(**fields):
    """A runner of the library's defaults with the given Params fields changed (a stage switched
    off, samples/benchmark/stage_value.py), for METHODS."""
    return _run_rcme(None, **fields)


def _run_opencv_f(flag):
    def run(p1, p2, K, budget):
        cv2.setRNGSeed(budget.seed)
        start = time.perf_counter()
        F, mask = cv2.findFundamentalMat(p1, p2, flag, budget.threshold,
                                         budget.opencv_confidence, budget.iterations)
        R = t = None
        ok = F is not None and F.shape == (3, 3) and mask is not None
        if ok and K is not None:
            R, t = motion_from_f(F, K, p1, p2, mask)
            ok = R is not None
        seconds = time.perf_counter() - start
        if not ok:
            return Estimate(False, NO_MODEL, mask=np.zeros(len(p1), bool), seconds=seconds)
        return Estimate(True, "ok", _normalized(F), R, t, mask.ravel() > 0, seconds)
    return run


def _run_opencv_e(flag):
    def run(p1, p2, K, budget):
        if K is None:
            return None  # needs a camera matrix
        cv2.setRNGSeed(budget.seed)
        start = time.perf_counter()
        E, mask = cv2.findEssentialMat(p1, p2, K, flag, budget.opencv_confidence,
                                       budget.threshold, budget.iterations)
        ok = E is not None and E.shape == (3, 3) and mask is not None
        R = t = None
        if ok:
            # recoverPose keeps the essential mask's inliers that pass cheirality
            _, R, t, _ = cv2.recoverPose(E, p1, p2, K, mask=mask.copy())
        seconds = time.perf_counter() - start
        if not ok:
            return Estimate(False, NO_MODEL, mask=np.zeros(len(p1), bool), seconds=seconds)
        Kinv = np.linalg.inv(K)
        return Estimate(True, "ok", _normalized(Kinv.T @ E @ Kinv), R, t, mask.ravel() > 0,
                        seconds)
    return run


def poselib_camera(K):
    """PoseLib's pinhole camera of the camera matrix K (its image taken as twice the principal
    point)."""
    return {"model": "PINHOLE", "width": int(round(2 * K[0, 2])),
            "height": int(round(2 * K[1, 2])),
            "params": [K[0, 0], K[1, 1], K[0, 2], K[1, 2]]}


def poselib_ransac_options(budget, confidence=DEFAULT_CONFIDENCE):
    """PoseLib's RANSAC options for the budget: its Sampson threshold, N as min and max
    iterations when exact; adaptive, its own bound at `confidence` and no minimum number of
    samples, as every other method runs (PoseLib's own default minimum is 100)."""
    return {"max_iterations": budget.iterations, "max_epipolar_error": budget.threshold,
            "seed": budget.seed,
            "min_iterations": 0 if budget.adaptive else budget.iterations,
            "success_prob": confidence if budget.adaptive else 1.0 - 1e-12}


def _run_poselib():
    """PoseLib's relative pose (5-point RANSAC with LO and a final bundle adjustment) with K:
    the same pixel threshold on its epipolar (Sampson) error, N as min and max iterations when
    exact, PoseLib's own adaptive bound at DEFAULT_CONFIDENCE otherwise."""
    def run(p1, p2, K, budget):
        if K is None:
            return None  # needs a camera matrix
        camera = poselib_camera(K)
        options = poselib_ransac_options(budget)
        start = time.perf_counter()
        pose, info = poselib.estimate_relative_pose(p1, p2, camera, camera, options, {})
        seconds = time.perf_counter() - start
        mask = np.asarray(info["inliers"], bool)
        if info["num_inliers"] < 5:
            return Estimate(False, NO_MODEL, mask=np.zeros(len(p1), bool), seconds=seconds)
        R, t = np.asarray(pose.R), np.asarray(pose.t).reshape(3, 1)
        Kinv = np.linalg.inv(K)
        F = Kinv.T @ metrics.skew(t.ravel()) @ R @ Kinv
        return Estimate(True, "ok", _normalized(F), R, t, mask, seconds)
    return run


def _run_poselib_f():
    """PoseLib's fundamental matrix (7-point RANSAC with LO and a final refinement), no K: the
    same pixel threshold on its Sampson error, N as for its relative pose."""
    def run(p1, p2, K, budget):
        options = poselib_ransac_options(budget)
        start = time.perf_counter()
        F, info = poselib.estimate_fundamental(p1, p2, options, {})
        seconds = time.perf_counter() - start
        mask = np.asarray(info["inliers"], bool)
        if info["num_inliers"] < 7 or not np.all(np.isfinite(F)):
            return Estimate(False, NO_MODEL, mask=np.zeros(len(p1), bool), seconds=seconds)
        return Estimate(True, "ok", _normalized(np.asarray(F)), None, None, mask, seconds)
    return run


# Display names of rcme's methods in the paper's spelling; a method the module gains later is
# still benchmarked, under its constant's name (METHOD_FOO_BAR -> "FOO_BAR").
RCME_DISPLAY_NAMES = {"METHOD_RCME": "RCME", "METHOD_PRCME": "pRCME",
                      "METHOD_STANDARD": "Standard", "METHOD_MLESAC": "MLESAC",
                      "METHOD_COV_RANSAC": "Cov-RANSAC"}


def rcme_methods(module=rcme):
    """Every METHOD_* constant of the rcme module, as (display name, value), in the order of
    their values: the benchmark covers whatever the library offers."""
    constants = sorted((int(getattr(module, name)), name) for name in dir(module)
                       if name.startswith("METHOD_"))
    return [(RCME_DISPLAY_NAMES.get(name, name[len("METHOD_"):]), value)
            for value, name in constants]


# name -> (runner, can it be held to exactly N hypotheses)
METHODS = {DEFAULT_METHOD: (_run_rcme(None), True)}
METHODS.update({name: (_run_rcme(value), True) for name, value in rcme_methods()})
METHODS.update({
    "cv FM_RANSAC": (_run_opencv_f(cv2.FM_RANSAC), True),
    "cv FM_LMEDS": (_run_opencv_f(cv2.FM_LMEDS), False),
    "cv USAC_DEFAULT": (_run_opencv_f(cv2.USAC_DEFAULT), False),
    "cv USAC_MAGSAC": (_run_opencv_f(cv2.USAC_MAGSAC), False),
    "cv USAC_ACCURATE": (_run_opencv_f(cv2.USAC_ACCURATE), False),
    "cv E RANSAC": (_run_opencv_e(cv2.RANSAC), True),
    "cv E USAC_MAGSAC": (_run_opencv_e(cv2.USAC_MAGSAC), False),
})
if poselib is not None:
    METHODS["PoseLib relpose"] = (_run_poselib(), True)
# Estimators of F alone, run by the F-only suite (f_only.py) and not by the main benchmark.
F_ONLY_METHODS = {}
if poselib is not None and hasattr(poselib, "estimate_fundamental"):
    F_ONLY_METHODS["PoseLib F"] = (_run_poselib_f(), True)
# The peers: no status, and no seed (OpenCV 4.6 ignores cv2.setRNGSeed; PoseLib's seed is
# taken, but the peers run once per pair and N).
PEER_METHODS = [m for m in list(METHODS) + list(F_ONLY_METHODS)
                if m.startswith("cv ") or m.startswith("PoseLib")]


def run(name, p1, p2, K, budget):
    """One call of the named method; None when it does not apply (E methods without K)."""
    runner = METHODS[name][0] if name in METHODS else F_ONLY_METHODS[name][0]
    return runner(np.ascontiguousarray(p1, np.float64),
                            np.ascontiguousarray(p2, np.float64), K, budget)
