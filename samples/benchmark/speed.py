#!/usr/bin/python3
"""Time per call of rcme's methods against PoseLib and OpenCV on the same matches: every
calibrated pair of ../shared/data (SIFT, as run_benchmark.py), one thread, exactly N = 1000
iterations and adaptive (at most N, every method at the same confidence, --confidence, 0.999 by
default, and with no minimum number of samples: PoseLib's min_iterations is 0). Every method has
the same inlier threshold (1.96 px: rcme's default sigma of 1 px). Writes a Markdown report with
the side-by-side table, the target ratios and the floor of the 8-point Standard.

    samples/benchmark/with_poselib.sh --speed          (PoseLib in its venv; see that script)
    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/speed.py   (without PoseLib)

A method's time on a pair is the fastest of --repeats calls (the least disturbed by the
machine's other work); the tables give the median over the pairs, and a ratio A / B is the
median of the per-pair ratios (pair by pair, as farm-bench pairs its runs). The floor is what the
hypotheses alone cost: N x (8-point solver time + n x ns per residual), from the perf suite's
solver/8-point and score-per-point/count (modules/rcme/perf), run once by this script. The
default's call in its parts (the setup, the loop, each stage after it: how often it runs, its time
per call, the verdicts it returns) comes from rcme_stage_costs (samples/benchmark/stage_costs.cpp)
on the same pairs; --stages-only writes that section alone."""
import json
import os
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np
import cv2

import datasets
import matching
import methods
import report
import run_benchmark
from methods import rcme, poselib

REPO_ROOT = run_benchmark.REPO_ROOT
# The adaptive runs' confidence, the same for every method (main() sets it from --confidence).
CONFIDENCE = 0.999


def rcme_runner(method=None, solver=None, local_optimization=None, fundamental_only=False,
                **fields):
    """method None: the library's defaults (Params()); else Params.asPublished(method), with
    the solver and local optimisation overridden when given, and any other Params field in
    fields; fundamental_only: without the camera matrix (an F, as findFundamentalMat)."""
    def run(p1, p2, K, N, adaptive):
        budget = methods.Budget(N, 1.0, 0, adaptive)
        params = methods.rcme_params(method, budget)
        if adaptive:
            params.confidence = CONFIDENCE
        if solver is not None:
            params.solver = solver
        if local_optimization is not None:
            params.localOptimization = local_optimization
        for name, value in fields.items():
            setattr(params, name, value)
        camera = np.zeros((0, 0)) if fundamental_only else K
        start = time.perf_counter()
        rcme.estimateRelativeMotion(p1, p2, camera, params)
        return time.perf_counter() - start
    return run


def exact_confidence(flag):
    """The confidence that holds OpenCV to maxIters. USAC stops at its adaptive bound unless the
    confidence is exactly 1 (log(1 - 1) = -inf); the old RANSAC replaces 1 by 0.99, and its
    largest accepted value still lets it stop early on pairs with many inliers."""
    usac = flag in (cv2.USAC_DEFAULT, cv2.USAC_ACCURATE, cv2.USAC_MAGSAC, cv2.USAC_PROSAC,
                    cv2.USAC_FAST, cv2.USAC_PARALLEL, cv2.USAC_FM_8PTS)
    return 1.0 if usac else methods.OPENCV_CONFIDENCE


def opencv_f(flag):
    def run(p1, p2, K, N, adaptive):
        confidence = CONFIDENCE if adaptive else exact_confidence(flag)
        start = time.perf_counter()
        cv2.findFundamentalMat(p1, p2, flag, methods.Budget(N, 1.0, 0).threshold, confidence, N)
        return time.perf_counter() - start
    return run


def opencv_e(flag):
    def run(p1, p2, K, N, adaptive):
        confidence = CONFIDENCE if adaptive else exact_confidence(flag)
        start = time.perf_counter()
        cv2.findEssentialMat(p1, p2, K, flag, confidence, methods.Budget(N, 1.0, 0).threshold, N)
        return time.perf_counter() - start
    return run


def poselib_runner():
    def run(p1, p2, K, N, adaptive):
        camera = methods.poselib_camera(K)
        options = methods.poselib_ransac_options(methods.Budget(N, 1.0, 0, adaptive), CONFIDENCE)
        start = time.perf_counter()
        poselib.estimate_relative_pose(p1, p2, camera, camera, options, {})
        return time.perf_counter() - start
    return run


def timed_methods():
    table = {
        "rcme default": rcme_runner(),
        "Standard 8-point": rcme_runner(rcme.METHOD_STANDARD),
        "Standard 7-point": rcme_runner(rcme.METHOD_STANDARD, rcme.SOLVER_SEVEN_POINT),
        "Standard 5-point": rcme_runner(rcme.METHOD_STANDARD, rcme.SOLVER_FIVE_POINT),
        "RCME 8-point": rcme_runner(rcme.METHOD_RCME),
        "RCME 5-point": rcme_runner(rcme.METHOD_RCME, rcme.SOLVER_FIVE_POINT),
        # USAC_ACCURATE's work: an F from the loop, without the stages after it (refinement to a
        # stable inlier set, final fit and covariance, the homography test)
        SAME_WORK: rcme_runner(rcme.METHOD_STANDARD, fundamental_only=True, refine=False,
                               degeneracyTest=False),
        "cv F USAC_ACCURATE": opencv_f(cv2.USAC_ACCURATE),
        "cv F RANSAC": opencv_f(cv2.FM_RANSAC),
        "cv E RANSAC": opencv_e(cv2.RANSAC),
        "cv E USAC_ACCURATE": opencv_e(cv2.USAC_ACCURATE),
        "cv E USAC_MAGSAC": opencv_e(cv2.USAC_MAGSAC),
        # findFundamentalMat's users have no camera matrix: the default without it.
        "rcme default, no K": rcme_runner(fundamental_only=True),
    }
    if poselib is not None:
        table["PoseLib relpose"] = poselib_runner()
    return table


# (numerator, denominator, limit) of the targets, each checked at exactly N and where
# marked adaptive.
TARGETS_EXACT = [("rcme default", "PoseLib relpose", 1.0),
                 ("Standard 8-point", "cv F USAC_ACCURATE", 1.0),
                 ("Standard 7-point", "cv F USAC_ACCURATE", 1.0),
                 ("RCME 8-point", "Standard 8-point", 1.3),
                 ("RCME 5-point", "Standard 5-point", 1.3)]
# (numerator, denominator, limit) checked in adaptive mode, what users run.
TARGETS_ADAPTIVE = [("rcme default", "PoseLib relpose", 1.0),
                    ("rcme default", "cv E USAC_MAGSAC", 1.3),
                    ("rcme default, no K", "cv F USAC_ACCURATE", 1.0)]
ADAPTIVE_RCME = ["rcme default", "Standard 8-point", "Standard 7-point", "Standard 5-point",
                 "RCME 8-point", "RCME 5-point"]
SAME_WORK = "Standard 8-point, F, no refinement or homography test"


def measure(pairs, table, N, adaptive, repeats):
    """{method: [seconds per pair]}; the calls of one pair interleave the methods, so a slow
    moment of the machine falls on all of them."""
    times = {name: [] for name in table}
    for index, pair in enumerate(pairs):
        p1 = np.ascontiguousarray(pair.points1, np.float64)
        p2 = np.ascontiguousarray(pair.points2, np.float64)
        best = {name: np.inf for name in table}
        for _ in range(repeats):
            for name, run in table.items():
                best[name] = min(best[name], run(p1, p2, pair.K, N, adaptive))
        for name in table:
            times[name].append(best[name])
        sys.stderr.write("\r%s N=%d: pair %d/%d" % ("adaptive" if adaptive else "exact", N,
                                                    index + 1, len(pairs)))
    sys.stderr.write("\n")
    return times


def ratio(times, a, b):
    if a not in times or b not in times:
        return None
    return float(np.median(np.asarray(times[a]) / np.asarray(times[b])))


def perf_floor(binary):
    """(8-point solver ns per sample, ns per residual of the inlier count) from the perf suite,
    on one core; None when the binary is missing."""
    if not os.path.exists(binary):
        return None
    out = subprocess.run(["taskset", "-c", "0", binary,
                          "--benchmark_filter=^(solver/8-point|score-per-point/count)$",
                          "--benchmark_format=json"], capture_output=True, text=True, check=True)
    results = {b["name"]: b for b in json.loads(out.stdout)["benchmarks"]}
    solver_ns = results["solver/8-point"]["cpu_time"]
    residual_ns = 1e9 / results["score-per-point/count"]["items_per_second"]
    return solver_ns, residual_ns


def stage_costs(binary, pairs, N, repeats):
    """{mode: [one run per pair]} of the default, from rcme_stage_costs (samples/benchmark/
    stage_costs.cpp: the setup, the loop and each stage after it, and the verdicts the stages
    returned); None when the binary is missing."""
    if not os.path.exists(binary):
        return None
    budget = methods.Budget(N, 1.0, 0)
    with tempfile.NamedTemporaryFile(suffix=".pairs", delete=False) as f:
        f.write(struct.pack("<i", len(pairs)))
        for pair in pairs:
            f.write(struct.pack("<i", len(pair.points1)))
            for array in (pair.K, pair.points1, pair.points2):
                f.write(np.ascontiguousarray(array, "<f8").tobytes())
    try:
        out = subprocess.run([binary, f.name, str(N), repr(CONFIDENCE), repr(budget.sigma),
                              repr(budget.threshold), str(repeats)],
                             capture_output=True, text=True, check=True)
    finally:
        os.unlink(f.name)
    return json.loads(out.stdout)


def stage_table(runs):
    """Per stage of the default: on how many pairs it ran, its median time per call, its share
    of the whole time, and what it did (verdicts by status, model revisions)."""
    total = sum(run["total"] for run in runs)
    rows = []
    for label, key in (("setup (data, components)", "setup"), ("the loop", "loop")):
        times = [run[key] for run in runs]
        rows.append([label, "%d" % len(runs), "%.3f" % (1000 * np.median(times)),
                     "%.0f %%" % (100 * sum(times) / total), ""])
    for k, stage in enumerate(runs[0]["stages"]):
        ran = [run["stages"][k] for run in runs if run["stages"][k]["ran"]]
        times = [s["seconds"] for s in ran]
        verdicts = {}
        for s in ran:
            if s["verdict"] >= 0:
                name = rcme.statusToString(s["verdict"])
                verdicts[name] = verdicts.get(name, 0) + 1
        did = ["%d x %s" % (count, name) for name, count in sorted(verdicts.items())]
        revised = sum(s["revised"] for s in ran)
        if revised:
            did.append("%d model revisions" % revised)
        rows.append([stage["name"], "%d" % len(ran),
                     "%.3f" % (1000 * np.median(times)) if times else "-",
                     "%.0f %%" % (100 * sum(times) / total), ", ".join(did)])
    rows.append(["whole call", "%d" % len(runs),
                 "%.3f" % (1000 * np.median([run["total"] for run in runs])), "100 %", ""])
    return report._table(["part", "ran on pairs", "median ms per call", "share of all time",
                          "verdicts and revisions"], rows)


def stage_section(stages, N, repeats):
    lines = ["## Cost per stage of the default", "",
             "The default's call in its parts (`rcme_stage_costs`, samples/benchmark/"
             "stage_costs.cpp: each stage after the loop wrapped in a timer, in a separate "
             "process on the same pairs; fastest of %d runs per pair and part). *The loop* "
             "includes local optimisation and the rivals' tracking; a verdict is the status a "
             "stage set (the final decision's success is the estimate standing)." % repeats, ""]
    for mode, label in (("adaptive", "adaptive (N <= %d)" % N), ("exact", "exactly N = %d" % N)):
        lines += ["%s%s:" % (label[0].upper(), label[1:]), "", stage_table(stages[mode]), ""]
    return lines


def write(path, pairs, N, exact, adaptive, floor, args, stages=None):
    names = list(exact)
    lines = ["# Speed: rcme against PoseLib and OpenCV on the same matches", "",
             "Generated by `samples/benchmark/speed.py` (%s); %s." % (
                 time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                 run_benchmark.machine_description()),
             "%d calibrated pairs (%d to %d matches, median %d), one thread, fastest of %d calls "
             "per pair; threshold %.2f px for every method; adaptive: confidence %g for every "
             "method, no minimum number of samples." % (
                 len(pairs), min(len(p.points1) for p in pairs),
                 max(len(p.points1) for p in pairs),
                 int(np.median([len(p.points1) for p in pairs])), args.repeats,
                 methods.Budget(N, 1.0, 0).threshold, CONFIDENCE), ""]
    rows = []
    for name in names:
        rows.append([name, "%.2f" % (1000 * np.median(exact[name])),
                     "%.2f" % (1000 * np.median(adaptive[name]))])
    lines += ["Median time per call, ms:", "",
              report._table(["method", "exactly N = %d" % N, "adaptive (N <= %d)" % N], rows), ""]
    rows = []
    for a, b, limit in TARGETS_EXACT:
        value = ratio(exact, a, b)
        if value is not None:
            rows.append(["%s / %s, exactly N" % (a, b), "%.2f" % value, "%.1f" % limit,
                         "met" if value <= limit else "**not met**"])
    for a, b, limit in TARGETS_ADAPTIVE:
        value = ratio(adaptive, a, b)
        if value is not None:
            rows.append(["%s / %s, adaptive" % (a, b), "%.2f" % value, "%.1f" % limit,
                         "met" if value <= limit else "**not met**"])
    for a in ADAPTIVE_RCME:
        value = ratio(adaptive, a, "cv F USAC_ACCURATE")
        if value is not None:
            rows.append(["%s / cv F USAC_ACCURATE, adaptive" % a, "%.2f" % value, "1.0",
                         "met" if value <= 1.0 else "**not met**"])
    value = ratio(adaptive, SAME_WORK, "cv F USAC_ACCURATE")
    if value is not None:  # not a target: what the stages after the loop cost
        rows.append(["%s / cv F USAC_ACCURATE, adaptive" % SAME_WORK, "%.2f" % value, "n/a",
                     "the same work, for reference"])
    if floor is not None:
        solver_ns, residual_ns = floor
        n = np.asarray([len(p.points1) for p in pairs], float)
        floor_s = N * (solver_ns + n * residual_ns) * 1e-9
        value = float(np.median(np.asarray(exact["Standard 8-point"]) / floor_s))
        rows.append(["Standard 8-point / floor, exactly N", "%.2f" % value, "2.0",
                     "met" if value <= 2.0 else "**not met**"])
        lines.append("The floor: N x (8-point solver %.0f ns + n x %.2f ns per residual), from "
                     "the perf suite on core 0 (`solver/8-point`, `score-per-point/count`); "
                     "median %.2f ms over the pairs." % (solver_ns, residual_ns,
                                                         1000 * np.median(floor_s)))
        lines.append("")
    lines += ["Targets (median of the per-pair ratios):", "",
              report._table(["ratio", "measured", "limit", ""], rows), ""]
    if stages is not None:
        lines += stage_section(stages, N, args.repeats)
    with open(path, "w") as f:
        f.write("\n".join(lines))
    sys.stderr.write("wrote %s\n" % path)


def main(argv=None):
    global CONFIDENCE
    ap = matching.benchmark_arguments(__doc__, REPO_ROOT,
                                      os.path.join(REPO_ROOT, "doc", "speed.md"))
    ap.add_argument("--iterations", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--confidence", type=float, default=CONFIDENCE,
                    help="of every method's adaptive termination (default %(default)s)")
    ap.add_argument("--max-pairs", type=int, default=0, help="every k-th pair to keep at most "
                    "this many (0: all)")
    ap.add_argument("--perf-binary", default=os.path.join(REPO_ROOT, "build", "bin",
                                                          "opencv_perf_rcme"))
    ap.add_argument("--stage-costs-binary", default=None,
                    help="samples/benchmark/stage_costs.cpp's program (default: build/bin/"
                    "rcme_stage_costs, its section left out when missing; given: required)")
    ap.add_argument("--stages-only", action="store_true", help="only the cost per stage of the "
                    "default (no side-by-side timing)")
    ap.add_argument("--quick", action="store_true", help="two reference frames per sequence, "
                    "at most 4 pairs, N = 100, one call each (ctest's smoke test)")
    args = ap.parse_args(argv)
    if args.quick:
        args.iterations, args.repeats, args.max_pairs = 100, 1, 4
    CONFIDENCE = args.confidence
    cv2.setNumThreads(1)
    if not any(datasets.load_all(args.data)):
        print("skipped: no data under %s (../shared/data/README.md)" % args.data)
        return run_benchmark.EXIT_SKIPPED
    bench_args = run_benchmark.parse_args(["--data", args.data, "--cache", args.cache]
                                          + (["--quick"] if args.quick else []))
    found, _ = run_benchmark.real_pairs(bench_args, matching.Matcher(args.cache))
    pairs = [p for p in found if p.K is not None]
    if args.max_pairs and len(pairs) > args.max_pairs:
        step = len(pairs) / args.max_pairs
        pairs = [pairs[int(k * step)] for k in range(args.max_pairs)]
    binary = args.stage_costs_binary or os.path.join(REPO_ROOT, "build", "bin",
                                                     "rcme_stage_costs")
    if args.stage_costs_binary and not os.path.exists(binary):
        print("no %s" % binary)
        return 1
    stages = stage_costs(binary, pairs, args.iterations, args.repeats)
    if args.stages_only:
        if stages is None:
            print("no %s" % binary)
            return 1
        with open(args.out, "w") as f:
            f.write("\n".join(stage_section(stages, args.iterations, args.repeats)))
        print(open(args.out).read())
        return 0
    table = timed_methods()
    exact = measure(pairs, table, args.iterations, False, args.repeats)
    adaptive = measure(pairs, table, args.iterations, True, args.repeats)
    write(args.out, pairs, args.iterations, exact, adaptive, perf_floor(args.perf_binary), args,
          stages)
    print(open(args.out).read())
    # Every method timed on every pair, or the table means nothing.
    complete = all(len(t) == len(pairs) and np.all(np.isfinite(t)) and np.all(np.asarray(t) > 0)
                   for times in (exact, adaptive) for t in times.values())
    complete = complete and (stages is None or all(len(stages[mode]) == len(pairs)
                                                   for mode in ("adaptive", "exact")))
    return 0 if pairs and complete else 1


if __name__ == "__main__":
    sys.exit(main())
