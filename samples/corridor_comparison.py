#!/usr/bin/python3
"""rcme's methods next to OpenCV's findFundamentalMat (FM_RANSAC) on the paper's corridor scenes
(Table I setting): the same correspondences, the same exactly-N iterations.

F estimates become motions the same way (E = K^T F K, cv2.recoverPose); rcme is also run
calibrated (rcme.estimateRelativeMotion with K, as rcme.recoverPose: Standard, RCME, pRCME, MLESAC,
Cov-RANSAC with SPRT). Errors: the paper's dq and dt, and the
rotation / translation-direction angles in degrees. Failures are counted by status: poor quality
input, degenerate (every sample degenerate, or a homography explains the inliers as well as F),
other (an empty F from OpenCV); the means are over the successes.

    PYTHONPATH=build/python /usr/bin/python3 samples/corridor_comparison.py --seeds 200
"""
import argparse
import os
import sys
import time

import numpy as np
import cv2

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "benchmark"))
from methods import (OPENCV_CONFIDENCE, Budget, motion_from_f, rcme,  # noqa: E402
                     rcme_methods, rcme_params)
from corridor import scene_params  # noqa: E402


def summarize(name, errors, failures, seconds, points, seeds):
    e = np.array(errors) if errors else np.full((1, 4), np.nan)
    points = "%6.1f" % np.mean(points) if points else "   n/a"
    pqi = 100.0 * failures.get(rcme.STATUS_POOR_QUALITY_INPUT, 0) / seeds
    degenerate = 100.0 * failures.get(rcme.STATUS_DEGENERATE_CONFIGURATION, 0) / seeds
    other = 100.0 * sum(failures.values()) / seeds - pqi - degenerate
    print("| %-28s | %6.3f (%5.3f) | %6.3f (%5.3f) | %7.2f | %7.2f | %5.1f %% | %5.1f %% "
          "| %5.1f %% | %6.2f | %s |" % (
              name, e[:, 0].mean(), e[:, 0].std(), e[:, 1].mean(), e[:, 1].std(),
              np.median(e[:, 2]), np.median(e[:, 3]), pqi, degenerate, other,
              1000 * np.median(seconds), points))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=200)
    ap.add_argument("--points", type=int, default=500)
    ap.add_argument("--inlier-ratio", type=float, default=0.5)
    ap.add_argument("--sigma", type=float, default=1.0)
    ap.add_argument("--iterations", type=int, default=1000)
    ap.add_argument("--corridor-width", type=float, default=None,
                    help="metres between the side walls (default: SceneParams')")
    ap.add_argument("--corridor-height", type=float, default=None,
                    help="metres between floor and ceiling (default: SceneParams')")
    args = ap.parse_args()

    threshold = Budget(args.iterations, args.sigma, 0).threshold
    calibrated = {"rcme %s, recoverPose" % name: value for name, value in rcme_methods()}
    runs = {name: ([], {}, [], []) for name in
            ["rcme Standard, F"] + list(calibrated) + ["OpenCV FM_RANSAC, F"]}

    def record(name, R, t, scene, seconds, status, points_per_hypothesis=None):
        errors, failures, times, points = runs[name]
        times.append(seconds)
        if points_per_hypothesis is not None:
            points.append(points_per_hypothesis)
        if R is None:
            failures[status] = failures.get(status, 0) + 1
            return
        m = rcme.compareMotion(R, t, scene.R, scene.t)
        errors.append((m.dq, m.dt, m.rotationDeg, m.translationDeg))

    for seed in range(args.seeds):
        sp = scene_params(args.points, args.inlier_ratio, args.sigma, seed)
        if args.corridor_width is not None:
            sp.corridorWidth = args.corridor_width
        if args.corridor_height is not None:
            sp.corridorHeight = args.corridor_height
        s = rcme.generateScene(sp)
        K, p1, p2 = s.cameraMatrix, s.points1, s.points2
        params = rcme_params(rcme.METHOD_STANDARD, Budget(args.iterations, args.sigma, seed))

        start = time.perf_counter()
        F, _, status = rcme.findFundamentalMat(p1, p2, params)
        seconds = time.perf_counter() - start
        ok = status == rcme.STATUS_SUCCESS
        record("rcme Standard, F", *(motion_from_f(F, K, p1, p2) if ok else (None, None)), s,
               seconds, status)

        # estimateRelativeMotion is what rcme.recoverPose runs; its report adds the points
        # evaluated per hypothesis (fewer than n with Cov-RANSAC's SPRT).
        for name, method in calibrated.items():
            params.method = method
            start = time.perf_counter()
            rep = rcme.estimateRelativeMotion(p1, p2, K, params)
            seconds = time.perf_counter() - start
            record(name, rep.R if rep.status == rcme.STATUS_SUCCESS else None, rep.t, s, seconds,
                   rep.status, rep.pointsPerHypothesis)

        # confidence ~1 keeps OpenCV's adaptive bound at maxIters: exactly N iterations too.
        cv2.setRNGSeed(seed)
        start = time.perf_counter()
        F, _ = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC, threshold, OPENCV_CONFIDENCE,
                                      args.iterations)
        seconds = time.perf_counter() - start
        ok = F is not None and F.shape == (3, 3)
        record("OpenCV FM_RANSAC, F", *(motion_from_f(F, K, p1, p2) if ok else (None, None)), s,
               seconds, None)

    print("corridor %g x %g m: %d seeds, n = %d, inlier ratio %.2f, sigma %.2f px, exactly N = %d, "
          "threshold %.2f px" % (sp.corridorWidth, sp.corridorHeight, args.seeds, args.points,
                                 args.inlier_ratio, args.sigma, args.iterations, threshold))
    print("| method | mean dq (std) | mean dt (std) | median rot. deg | median transl. deg "
          "| PQI | degenerate | other failure | median ms | points / hypothesis |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, (errors, failures, times, points) in runs.items():
        summarize(name, errors, failures, times, points, args.seeds)


if __name__ == "__main__":
    main()
