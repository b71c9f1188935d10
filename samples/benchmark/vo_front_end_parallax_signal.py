"""A scale-free form of the translation's uncertainty on the VO-front-end suite (issue 39): the
reported translation std against what the inliers' parallax supports,

    z = translationStdDeg [rad] * median parallax of the inliers [px] * sqrt(inliers) / noiseSigma [px]

(the std a translation direction fixed by n points with that parallax and that noise would have,
up to the geometry's factor, which z is). Parallax: the flow left after removing the returned
rotation, K R K^-1 x1 to x2. For every moving and after-stale pair of the suite (KLT and ORB,
KITTI 01 and 06) it runs rcme's default (rcme.Params() with the suite's threshold, N and seed)
and prints, per input, z's distribution over the right answers returned with success and z of
each wrong one. A measurement, not a library signal (doc/vo_front_end.md).

With --suites it measures z on every suite with K too, split into tune and report data: the main
benchmark's calibrated pairs (templeSR and KITTI-06 tune, the others report), the sparse suite
(report), the synthetic corridor scenes and hard cases of the benchmark (tune), and the VO suite
split by the first frame (KITTI 06 and KITTI 01 with an even first frame tune, KITTI 01 odd
report). Each at the suite's own settings (sigma 1 px, threshold 1.96 px, the suite's N; synthetic
scenes at their own sigma and N).

    PYTHONPATH=build/python python3 samples/benchmark/vo_front_end_parallax_signal.py
    PYTHONPATH=build/python python3 samples/benchmark/vo_front_end_parallax_signal.py --suites"""
import argparse
import os
import sys

import numpy as np

import corridor
import datasets
import hard_cases
import matching
import methods
import metrics
import run_benchmark
import sparse_pairs
import vo_front_end
from methods import rcme


def parallax_signal(pair, budget=None, model_based=False):
    """(z, right) of rcme's default on the pair, or None when it does not return a motion.
    model_based: z of the final fit's covariance at the stated sigma (useEstimatedNoise off, the
    covariance the decisions read before the reported one is computed), over that sigma."""
    p1 = np.ascontiguousarray(pair.points1, np.float64)
    p2 = np.ascontiguousarray(pair.points2, np.float64)
    budget = budget or methods.Budget(vo_front_end.N, 1.0, 0, adaptive=True)
    params = methods.rcme_params(None, budget)
    params.useEstimatedNoise = not model_based
    report = rcme.estimateRelativeMotion(p1, p2, pair.K, params)
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
    noise = params.sigma if model_based else report.noiseSigma
    z = np.radians(report.translationStdDeg) * np.median(parallax) * np.sqrt(inliers.sum()) / noise
    return float(z), right


def _first_frame(pair_name):
    return int(pair_name.split()[-1].split("-")[0])


def suite_pairs(data):
    """(suite, group, split, pair, budget) of every suite with K (see the module's doc)."""
    cache = os.path.join(vo_front_end.REPO_ROOT, "build", "benchmark_cache")
    matcher = matching.Matcher(cache)
    selection = argparse.Namespace(data=data, max_references=0, quick=False)
    dense = run_benchmark.real_pairs(selection, matcher)[0]
    main_budget = methods.Budget(run_benchmark.DEFAULT_SETTINGS_N, 1.0, 0, adaptive=True)
    for pair in dense:
        if pair.K is not None and pair.R_gt is not None:
            split = "tune" if pair.dataset.split()[0] in ("templeSR", "KITTI-06") else "report"
            yield "main", pair.dataset, split, pair, main_budget
    sequences = datasets.load_all(data)[0]
    for pair in sparse_pairs.sparse_pairs(sequences, dense, matcher):
        if pair.R_gt is not None:
            yield "sparse", pair.dataset, "report", pair, main_budget
    synthetic = [corridor.corridor_pair(500, w, s, seed) for w, s in
                 [(0.3, 1.0), (0.5, 1.0), (0.7, 1.0), (0.5, 0.5), (0.5, 2.0)] for seed in range(10)]
    for pair in synthetic + hard_cases.hard_case_pairs(2):
        if pair.K is not None and pair.R_gt is not None:
            n = pair.iterations or run_benchmark.DEFAULT_SETTINGS_N
            yield "synthetic", pair.dataset, "tune", pair, methods.Budget(
                n, pair.sigma or 1.0, 0, adaptive=True)
    for label, sequence in vo_front_end.load_sequences(data):
        for name in vo_front_end.INPUTS:
            for kind, pair, _ in vo_front_end.vo_pairs(sequence, label, inputs=(name,)):
                if kind not in ("i+1", "i+2", "after stale"):
                    continue
                split = ("tune" if "06" in label or _first_frame(pair.name) % 2 == 0
                         else "report")
                yield "VO", "%s %s" % (label, name), split, pair, None


def main_suites(data, model_based):
    groups = {}
    for suite, group, split, pair, budget in suite_pairs(data):
        try:
            result = parallax_signal(pair, budget, model_based)
        except Exception as error:  # a pair the signal cannot be measured on (no inlier)
            sys.stderr.write("%s %s: %s\n" % (group, pair.name, error))
            continue
        if result is None or not np.isfinite(result[0]):
            continue
        right, wrong = groups.setdefault((split, suite, group), ([], []))
        (right if result[1] else wrong).append((result[0], pair.name))
    print("| split | suite | dataset | right answers | z: median | 95 % | max "
          "| wrong answers (z) |")
    print("|---|---|---|---|---|---|---|---|")
    largest = {}
    for (split, suite, group), (right, wrong) in sorted(groups.items()):
        z = np.sort([value for value, _ in right])
        if len(z):
            largest[split] = max(largest.get(split, 0.0), z[-1])
        print("| %s | %s | %s | %d | %s | %s | %s | %s |" % (
            split, suite, group, len(z), "%.2f" % np.median(z) if len(z) else "-",
            "%.2f" % np.quantile(z, 0.95) if len(z) else "-", "%.2f" % z[-1] if len(z) else "-",
            ", ".join("%s (%.1f)" % (name, value) for value, name in sorted(wrong)) or "none"))
    print("\nlargest z of a right answer: " + ", ".join(
        "%s %.2f" % item for item in sorted(largest.items())))
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(vo_front_end.REPO_ROOT, "..", "shared", "data"))
    ap.add_argument("--suites", action="store_true",
                    help="every suite with K, split into tune and report data")
    ap.add_argument("--model-based", action="store_true",
                    help="z of the model-based covariance at the stated sigma, not the "
                    "reported one")
    args = ap.parse_args(argv)
    if args.suites:
        return main_suites(args.data, args.model_based)
    print("| input | right answers | z: median | 95 % | max | wrong answers (z) |")
    print("|---|---|---|---|---|---|")
    for label, sequence in vo_front_end.load_sequences(args.data):
        for name in vo_front_end.INPUTS:
            right, wrong = [], []
            for kind, pair, _ in vo_front_end.vo_pairs(sequence, label, inputs=(name,)):
                if kind not in ("i+1", "i+2", "after stale"):
                    continue
                result = parallax_signal(pair, model_based=args.model_based)
                if result is not None:
                    (right if result[1] else wrong).append((result[0], pair.name))
            z = np.sort([value for value, _ in right])
            print("| %s %s | %d | %.2f | %.2f | %.2f | %s |" % (
                label, name, len(z), np.median(z), np.quantile(z, 0.95), z[-1],
                ", ".join("%s (%.1f)" % (pair_name, value) for value, pair_name in wrong) or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
