#!/usr/bin/python3
"""What each stage of the default costs and what it buys: the default's call in its parts
(rcme_stage_costs, as speed.py's "Cost per stage"), then the default with one stage (or the loop's
sample count) switched off through its Params field, beside the default: the time it saves per call
and what the benchmark's confusion cells become without it. Writes doc/benchmark/stage_value.md.

    samples/benchmark/with_poselib.sh --stage-costs [options]
    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/stage_value.py [options]

Time: the calibrated pairs of speed.py (every calibrated pair of ../shared/data, SIFT), one
thread, each pair's calls of every variant interleaved, the fastest of --repeats per pair and
variant; adaptive at speed.py's confidence (0.999), exactly N = 1000, and without the camera
matrix (adaptive, the same pairs, as speed.py's "rcme default, no K"). A change is the median over
the pairs of (variant - default), its share that over the default's median.
Cells: the suites of run_benchmark.py's confusion summary, run as it runs them (exactly N = 1000:
every real pair with --seeds seeds, the corridor and the hard cases with one; adaptive at the
benchmark's confidence 0.99, seed 0): right / undetected / caught / false alarm, as its report
counts them."""
import os
import sys
import time

import numpy as np
import cv2

import evaluate
import hard_cases
import matching
import methods
import report
import run_benchmark
import speed

REPO_ROOT = run_benchmark.REPO_ROOT
N = 1000  # main() sets it from --iterations

# (label, what it switches off, Params fields). A stage after the loop without a Params switch
# (candidate selection, the residual covariance, the final decision) has no row.
VARIANTS = [
    ("default", "", {}),
    ("USAC's sample count", "the loop's extra samples with K: cleanSampleSuccessRate 1 (default: "
     "0.3 with K, 1 without)",
     {"cleanSampleSuccessRate": 1.0}),
    ("no local optimisation", "LO, its inner sampling and the final polish: localOptimization "
     "false",
     {"localOptimization": False}),
    ("no refinement", "refinement, final fit, covariance, uncertainty bound: refine false",
     {"refine": False}),
    ("no homography test", "HomographyDegeneracyTest: degeneracyTest false",
     {"degeneracyTest": False}),
    ("no rival decisions", "RivalMotionDecision, RivalSelectionAtDataNoise: ambiguityMargin 0",
     {"ambiguityMargin": 0.0}),
    ("no rotation bound", "UncertaintyBound's rotation test: maxRotationStdDeg 0",
     {"maxRotationStdDeg": 0.0}),
    ("no translation bound", "UncertaintyBound's translation test and ChanceSupportTest's "
     "moving points: maxTranslationStdDeg 0", {"maxTranslationStdDeg": 0.0}),
]
CELLS = ("returned_right", "returned_wrong", "flagged_wrong", "flagged_right")


def cell_runs(real, corridor, hard, seeds, sigma):
    """{(variant, mode, suite): [rows]} over the benchmark's suites (suite "real" or
    "synthetic"), the default's variants only."""
    rows = {}
    for label, _, fields in VARIANTS:
        name = "rcme " + label
        methods.METHODS[name] = (methods.default_runner(**fields), True)
        for suite, pairs, suite_seeds in (("real", real, seeds), ("synthetic", corridor, 1),
                                          ("synthetic", hard, 1)):
            exact = rows.setdefault((label, "exact", suite), [])
            adaptive = rows.setdefault((label, "adaptive", suite), [])
            for pair in pairs:
                pair_n = N if pair.iterations is None else pair.iterations
                pair_sigma = pair.sigma if pair.sigma is not None else sigma
                for seed in range(suite_seeds):
                    exact.append(evaluate.evaluate(name, pair,
                                                   methods.Budget(pair_n, pair_sigma, seed)))
                adaptive.append(evaluate.evaluate(name, pair, methods.Budget(
                    pair_n, pair_sigma, 0, adaptive=True)))
        sys.stderr.write("cells: %s\n" % label)
    return {key: [r for r in runs if r is not None] for key, runs in rows.items()}


def cells(rows):
    counts = report.confusion_counts(rows)
    return "%d / %d / %d / %d" % tuple(counts[key] for key in CELLS)


def cell_table(rows):
    """A row per variant and mode: the four cells per suite (the real pairs split as the
    benchmark's summary splits them: with a pose, or F-only) and over all suites."""
    lines = []
    for mode, mode_label in (("adaptive", "adaptive"), ("exact", "exactly N = %d" % N)):
        for label, _, _ in VARIANTS:
            real, synthetic = rows[(label, mode, "real")], rows[(label, mode, "synthetic")]
            pose = report._pose_datasets(real)
            lines.append([mode_label, label, cells([r for r in real if r["dataset"] in pose]),
                          cells([r for r in real if r["dataset"] not in pose]),
                          cells(synthetic), cells(real + synthetic)])
    return report._table(["mode", "variant", "calibrated real pairs", "F-only real pairs",
                          "synthetic (corridor, hard cases)", "all suites"], lines)


def time_table(pairs, repeats):
    """Per variant: median ms per call and the median saving against the default (ms, share);
    and whether every variant was timed on every pair."""
    columns = []
    for mode, adaptive, no_k in (("adaptive", True, False), ("exactly N = %d" % N, False, False),
                                 ("adaptive, no K", True, True)):
        table = {label: speed.rcme_runner(fundamental_only=no_k, **fields)
                 for label, _, fields in VARIANTS}
        columns.append((mode, speed.measure(pairs, table, N, adaptive, repeats)))
    lines = []
    for label, what, _ in VARIANTS:
        line = [label, what]
        for _, times in columns:
            default = np.asarray(times["default"])
            own = np.asarray(times[label])
            saved = float(np.median(default - own))
            line.append("%.3f" % (1000 * np.median(own)) if label == "default" else
                        "%.3f (%+.3f, %+.0f %%)" % (1000 * np.median(own), -1000 * saved,
                                                   -100 * saved / np.median(default)))
        lines.append(line)
    complete = all(len(t) == len(pairs) and np.all(np.isfinite(t)) and np.all(np.asarray(t) > 0)
                   for _, times in columns for t in times.values())
    return report._table(["variant", "switched off"] + [
        "%s: median ms (change, share of the default)" % mode for mode, _ in columns],
        lines), complete


def main(argv=None):
    global N
    ap = matching.benchmark_arguments(
        __doc__, REPO_ROOT, os.path.join(REPO_ROOT, "doc", "benchmark", "stage_value.md"))
    ap.add_argument("--repeats", type=int, default=3, help="calls per pair and variant, timing")
    ap.add_argument("--seeds", type=int, default=3, help="seeds per real pair, exactly N")
    ap.add_argument("--iterations", type=int, default=N, help="N (default %(default)s)")
    ap.add_argument("--stage-costs-binary",
                    default=os.path.join(REPO_ROOT, "build", "bin", "rcme_stage_costs"))
    ap.add_argument("--quick", action="store_true",
                    help="a few pairs per dataset, one seed, one call each, N = 200 (ctest's "
                    "smoke test)")
    args = ap.parse_args(argv)
    N = 200 if args.quick else args.iterations
    cv2.setNumThreads(1)
    start, load = time.time(), os.getloadavg()
    bench_args = run_benchmark.parse_args(["--data", args.data, "--cache", args.cache]
                                          + (["--quick"] if args.quick else []))
    if args.quick:
        args.repeats, args.seeds = 1, 1
    real, _ = run_benchmark.real_pairs(bench_args, matching.Matcher(args.cache))
    if not real:
        print("skipped: no data under %s" % args.data)
        return run_benchmark.EXIT_SKIPPED
    calibrated = [p for p in real if p.K is not None]
    stages = speed.stage_costs(args.stage_costs_binary, calibrated, N, args.repeats)
    if stages is None:
        print("no %s" % args.stage_costs_binary)
        return 1
    times, timed = time_table(calibrated, args.repeats)
    rows = cell_runs(real, run_benchmark.corridor_pairs(bench_args),
                     hard_cases.hard_case_pairs(bench_args.hard_seeds), args.seeds,
                     bench_args.sigma)
    lines = [
        "# What each stage of the default costs and buys", "",
        "Generated by `samples/benchmark/stage_value.py` (`with_poselib.sh --stage-costs`, "
        "%s, %.0f s; load average %.2f / %.2f / %.2f at the start on %d logical CPUs); %s." % (
            time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), time.time() - start, *load,
            os.cpu_count(), run_benchmark.machine_description()), ""]
    lines += speed.stage_section(stages, N, args.repeats)
    lines += [
        "## The default with one part switched off", "",
        "Time: %d calibrated pairs, one thread, the variants' calls interleaved per pair, the "
        "fastest of %d per pair and variant; adaptive at confidence %g (speed.py's), exactly N = "
        "%d, and adaptive without the camera matrix on the same pairs. A change is the median "
        "over the pairs of (variant - default), its share that over the default's median." % (
            len(calibrated), args.repeats, speed.CONFIDENCE, N), "",
        times, "",
        "Cells (right / undetected / caught / false alarm, as the benchmark's confusion summary "
        "counts them): exactly N = %d with %d seed(s) per real pair, adaptive at confidence %g "
        "(the benchmark's), seed 0; corridor and hard cases one run each. The default's row is "
        "the benchmark's `rcme default`." % (N, args.seeds, methods.DEFAULT_CONFIDENCE), "",
        cell_table(rows), ""]
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(open(args.out).read())
    # Every variant timed on every pair and run on every suite, or the tables mean nothing.
    ran = all(rows[(label, mode, suite)] for label, _, _ in VARIANTS
              for mode in ("exact", "adaptive") for suite in ("real", "synthetic"))
    return 0 if timed and ran else 1


if __name__ == "__main__":
    sys.exit(main())
