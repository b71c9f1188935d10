"""A scale-free form of the translation's uncertainty on the VO-front-end suite (issue 39): the
reported translation std against what the inliers' parallax supports,

    z = translationStdDeg [rad] * median parallax of the inliers [px] * sqrt(inliers) / noiseSigma [px]

(the std a translation direction fixed by n points with that parallax and that noise would have,
up to the geometry's factor, which z is). Parallax: the flow left after removing the returned
rotation, K R K^-1 x1 to x2. For every moving and after-stale pair of the suite (KLT and ORB,
KITTI 01 and 06) it runs rcme's default (rcme.Params() with the suite's threshold, N and seed)
and prints, per input, z's distribution over the right answers returned with success and z of
each wrong one. A measurement, not a library signal (doc/vo_front_end.md).

    PYTHONPATH=build/python python3 samples/benchmark/vo_front_end_parallax_signal.py"""
import argparse
import os
import sys

import numpy as np

import methods
import metrics
import vo_front_end
from methods import rcme


def parallax_signal(pair):
    """(z, right) of rcme's default on the pair, or None when it does not return a motion."""
    p1 = np.ascontiguousarray(pair.points1, np.float64)
    p2 = np.ascontiguousarray(pair.points2, np.float64)
    budget = methods.Budget(vo_front_end.N, 1.0, 0, adaptive=True)
    report = rcme.estimateRelativeMotion(p1, p2, pair.K, methods.rcme_params(None, budget))
    if report.status != rcme.STATUS_SUCCESS:
        return None
    R = np.asarray(report.R)
    inliers = np.asarray(report.mask).ravel().astype(bool)
    error = rcme.compareMotion(R, np.asarray(report.t).reshape(3, 1), pair.R_gt,
                               pair.t_gt.reshape(3, 1))
    right = not metrics.pose_failure(error.rotationDeg, error.translationDeg)
    H = pair.K @ R @ np.linalg.inv(pair.K)
    x1 = np.c_[p1[inliers], np.ones(inliers.sum())] @ H.T
    parallax = np.linalg.norm(p2[inliers] - x1[:, :2] / x1[:, 2:], axis=1)
    z = (np.radians(report.translationStdDeg) * np.median(parallax) * np.sqrt(inliers.sum()) /
         report.noiseSigma)
    return float(z), right


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(vo_front_end.REPO_ROOT, "..", "shared", "data"))
    args = ap.parse_args(argv)
    print("| input | right answers | z: median | 95 % | max | wrong answers (z) |")
    print("|---|---|---|---|---|---|")
    for label, sequence in vo_front_end.load_sequences(args.data):
        for name in vo_front_end.INPUTS:
            right, wrong = [], []
            for kind, pair, _ in vo_front_end.vo_pairs(sequence, label, inputs=(name,)):
                if kind not in ("i+1", "i+2", "after stale"):
                    continue
                result = parallax_signal(pair)
                if result is not None:
                    (right if result[1] else wrong).append((result[0], pair.name))
            z = np.sort([value for value, _ in right])
            print("| %s %s | %d | %.2f | %.2f | %.2f | %s |" % (
                label, name, len(z), np.median(z), np.quantile(z, 0.95), z[-1],
                ", ".join("%s (%.1f)" % (pair_name, value) for value, pair_name in wrong) or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
