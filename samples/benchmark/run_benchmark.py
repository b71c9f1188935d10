#!/usr/bin/python3
"""rcme's methods against OpenCV's on the paper's experiments, on the same correspondences:
the corridor (Table I) and every real sequence and pair in ../shared/data (Table II).

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/run_benchmark.py
    ... --quick            (a subset in under two minutes; what `make test` runs)
    ... --sparse-only      (the sparse-pairs suite alone: sparse_pairs.py)

Writes <out>/report.md and PNG plots (default doc/benchmark/), and the sparse-pairs suite's
<out>/sparse_pairs.md; caches SIFT matches under build/benchmark_cache/. See doc/benchmark.md."""
import datetime
import json
import os
import platform
import subprocess
import sys
import time

import numpy as np
import cv2

import corridor
import datasets
import evaluate
import hard_cases
import matching
import methods
import pairs
import report
import sparse_pairs

EXIT_SKIPPED = 77  # CTest's SKIP_RETURN_CODE
PLOT_FILES = ["cumulative_rotation.png", "gt_failure_rates.png", "pqi_rates.png",
              "degenerate_rates.png", "paper_failure_rates.png"]
REPORT_FILES = ["report.md"] + PLOT_FILES
SPARSE_REPORT = "sparse_pairs.md"
REPO_ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


class Progress:
    """A one-line progress bar with an estimate of the time left, on stderr."""

    def __init__(self, total, label):
        self.total, self.label, self.done, self.start = max(total, 1), label, 0, time.time()
        self.shown = 0.0

    def step(self, count=1):
        self.done += count
        now = time.time()
        if now - self.shown < 0.5 and self.done < self.total:
            return  # redraw at most twice a second: logs stay short
        self.shown, elapsed = now, now - self.start
        left = elapsed / self.done * (self.total - self.done) if self.done else 0
        filled = int(30 * self.done / self.total)
        sys.stderr.write("\r%-10s [%s%s] %d/%d %4.0fs left " % (
            self.label, "#" * filled, "." * (30 - filled), self.done, self.total, left))
        if self.done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def machine_description():
    model = platform.processor() or platform.machine()
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.split("\n"):
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "%s, %d logical CPUs, %s, Python %s, OpenCV %s" % (
        model, os.cpu_count() or 0, platform.platform(), platform.python_version(),
        cv2.__version__)


def parse_args(argv):
    ap = matching.benchmark_arguments(__doc__, REPO_ROOT,
                                      os.path.join(REPO_ROOT, "doc", "benchmark"))
    ap.add_argument("--quick", action="store_true",
                    help="a few pairs per dataset, N = 200, one seed")
    ap.add_argument("--iterations", type=int, nargs="+", default=[200, 500, 1000])
    ap.add_argument("--seeds", type=int, default=3, help="seeds per real pair")
    ap.add_argument("--corridor-seeds", type=int, default=50)
    ap.add_argument("--hard-seeds", type=int, default=10,
                    help="seeds per case of the hard-case suite (hard_cases.py)")
    ap.add_argument("--hard-only", action="store_true",
                    help="run the hard-case suite alone, add it to the last run's record in "
                         "--cache and rewrite the report")
    ap.add_argument("--sparse-only", action="store_true",
                    help="run the sparse-pairs suite alone (sparse_pairs.py) and write its report "
                         "(%s) only; exit 1 unless every method ran on it" % SPARSE_REPORT)
    ap.add_argument("--max-references", type=int, default=0, metavar="K",
                    help="at most K evenly spaced reference frames per sequence (0: all)")
    ap.add_argument("--sigma", type=float, default=1.0, help="noise (px); threshold 1.96 sigma")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite the report and plots from the last run's record in --cache")
    ap.add_argument("--check-rcme-gt-failure", type=float, default=None, metavar="PERCENT",
                    help="exit 1 unless the report, the plots and every method are there and "
                         "RCME's GT failure rate on the real pairs with a pose is at most this")
    args = ap.parse_args(argv)
    if args.quick:
        args.iterations, args.seeds, args.corridor_seeds, args.max_references = [200], 1, 10, 2
        args.hard_seeds = 2
    return args


def real_pairs(args, matcher):
    sequences, raw_pairs = datasets.load_all(args.data)
    selected, notes = [], []
    for sequence in sequences:
        max_gap = 10 if sequence.name.startswith("KITTI") else 3
        references = list(range(len(sequence.images) - 1))
        if args.max_references and args.max_references < len(references):
            spacing = len(references) / args.max_references
            references = [references[int(k * spacing)] for k in range(args.max_references)]
        chosen, rejected = pairs.select_sequence_pairs(sequence, matcher, max_gap, references)
        selected += chosen
        notes.append("| %s | %d | %d | %d | %d | %d |" % (
            sequence.name, len(references), len(chosen), rejected["matches"],
            rejected["parallax"], rejected["homography"]))
        sys.stderr.write("pairs: %s %d\n" % (sequence.name, len(chosen)))
    if args.quick:
        keep = {"adelaide/bonython", "adelaide/library", "adelaide/physics", "magsac/corr",
                "magsac/booksh"}
        raw_pairs = [p for p in raw_pairs if p.name in keep]
    labelled = pairs.labelled_pairs(raw_pairs, matcher)
    return selected + labelled, notes


def corridor_pairs(args):
    ratios, sigmas = ([0.5], [1.0]) if args.quick else ([0.3, 0.5, 0.7], [0.5, 1.0, 2.0])
    configs = [(w, args.sigma) for w in ratios] + [(0.5, s) for s in sigmas if s != args.sigma]
    return [corridor.corridor_pair(500, w, s, seed)
            for w, s in configs for seed in range(args.corridor_seeds)]


def run_all(task_pairs, iterations, seeds, sigma, label):
    """Every method on every pair, N and seed. OpenCV 4.6's estimators take no seed (they
    ignore cv2.setRNGSeed and draw the same samples on every call), so they run once per pair
    and N; their rates are the same as over every seed. PoseLib (when installed, see
    with_poselib.sh) runs once per pair and N too, with seed 0."""
    tasks = [(pair, N, seed, method) for pair in task_pairs for N in iterations
             for seed in range(seeds) for method in methods.METHODS
             if seed == 0 or method not in methods.PEER_METHODS]
    progress, rows = Progress(len(tasks), label), []
    for pair, N, seed, method in tasks:
        budget = methods.Budget(N if pair.iterations is None else pair.iterations,
                                pair.sigma if pair.sigma is not None else sigma, seed)
        row = evaluate.evaluate(method, pair, budget)
        if row is not None:
            rows.append(row)
        progress.step()
    return rows


def write_report(args, run):
    """The report and its plots from one run's record (see main)."""
    rows_synthetic, rows_real = run["synthetic"], run["real"]
    os.makedirs(args.out, exist_ok=True)
    names = list(methods.METHODS)
    real_datasets = []
    for r in rows_real:
        if r["dataset"] not in real_datasets:
            real_datasets.append(r["dataset"])
    N_max = max(args.iterations)
    png = report.write_plots(rows_real, names, real_datasets, args.out, N_max)
    sigma = args.sigma
    inexact = [m for m, (_, exact) in methods.METHODS.items() if not exact]
    lines = [
        "# Benchmark: rcme against OpenCV on the paper's experiments\n",
        "Generated by `samples/benchmark/run_benchmark.py`; do not edit by hand.\n",
        "- Command: `%s`" % run["command"],
        "- Date: %s; wall time %.0f s (run under `nice` next to other jobs on a shared "
        "machine: times are comparable between methods of one run, not absolute)" % (
            run["date"], run["elapsed"]),
        "- Machine: %s" % run["machine"],
        "- rcme module: `%s`" % os.path.relpath(methods.rcme.__file__, REPO_ROOT),
        "- Real pairs: noise sigma %.2f px, inlier threshold %.2f px for every method (rcme: "
        "Sampson distance; OpenCV: its own distance, Sampson or distance to the epipolar line); "
        "corridor: the sigma the scenes were generated with, threshold 1.96 sigma. N in %s; %d "
        "seed(s) per real pair, %d corridor scenes per setting; %s." % (
            sigma, methods.Budget(1, sigma, 0).threshold, args.iterations, args.seeds,
            args.corridor_seeds,
            "at most %d reference frames per sequence, evenly spaced" % args.max_references
            if args.max_references else "every frame of a sequence is a reference frame"),
        "- rcme's methods run exactly N hypotheses (`exactIterations`). OpenCV's get "
        "maxIters = N and confidence 1 - 1e-12, so the adaptive bound does not stop them early; "
        "FM_RANSAC and findEssentialMat's RANSAC then draw exactly N samples, but **%s cannot be "
        "held to exactly N** (LMedS ignores the threshold; the USAC presets add local "
        "optimisation, SPRT and their own termination). OpenCV 4.6's estimators ignore "
        "`cv2.setRNGSeed` and repeat the same samples on every call, so they run once per pair "
        "and N." % ", ".join(inexact),
        "- Motions: rcme's methods get K (`estimateRelativeMotion`); OpenCV's F becomes a motion "
        "as E = K^T F K and `cv2.recoverPose` on its inliers; `cv E ...` is `findEssentialMat` + "
        "`recoverPose` (n/a without K). Times are wall times per call, including recoverPose.",
        "- " + report.THRESHOLDS_TEXT + "\n",
    ]
    if rows_synthetic:
        lines += ["## Synthetic: the corridor (Table I)\n",
                  "Scene (`rcme.generateScene`, SCENE_CORRIDOR, doc/synthetic.md): %s; both "
                  "cameras free-flying with yaw/pitch/roll in +-15 deg, baseline direction "
                  "uniform. dq, dt: the paper's quaternion and translation errors (mean, std) "
                  "over the runs with a model; precision / recall of the true inliers (median)."
                  "\n" % corridor.describe_scene(500),
                  report.synthetic_tables(rows_synthetic, names)]
    lines += ["## Real data (Table II)\n",
              "Sequences: from every reference frame, the first of the next frames (10 for "
              "KITTI, 3 otherwise) with >= %d SIFT matches (ratio test 0.8, mutual), a median "
              "parallax >= %.0f deg over >= %d matches that triangulate in front of both cameras "
              "under the true motion, and ORB-SLAM's R_H = S_H / (S_H + S_F) <= %.2f (above it "
              "ORB-SLAM initialises from a homography: planar or rotation-only pairs)." % (
                  pairs.MIN_MATCHES, pairs.MIN_PARALLAX_DEG, pairs.MIN_TRIANGULATED,
                  pairs.MAX_HOMOGRAPHY_RATIO),
              "AdelaideRMF: the given correspondences; true inliers = every label >= 1 (the "
              "scenes are static: one F explains all the labelled structures), so precision "
              "and recall are against the labels. MAGSAC vpts pairs: SIFT matches (the label-0 "
              "rows of their *_pts.txt do not fit the annotated geometry on several pairs), "
              "scored by the hand-annotated matches (F error). Neither has K: pose metrics and "
              "the E methods are n/a there.\n",
              "| sequence | reference frames | pairs | rejected: matches | rejected: parallax "
              "| rejected: homography |", "|---|---|---|---|---|---|"] + run["notes"] + [""]
    lines += ["### All real pairs\n", report.CELL_LEGEND + " Errors and times at N = %d.\n"
              % N_max, report.overview_table(rows_real, names, args.iterations)]
    for N in args.iterations:
        lines += ["### Table II style, N = %d\n" % N, report.CELL_LEGEND + "\n",
                  report.table_two(rows_real, names, real_datasets, N)]
    lines += ["### Per dataset\n"]
    for N in args.iterations:
        for dataset in real_datasets:
            lines += ["**%s, N = %d**\n" % (dataset, N),
                      report.detail_table(rows_real, names, dataset, N)]
    lines += confusion_section(run, names, real_datasets, N_max)
    lines += ["### Time per call: RCME against OpenCV USAC_ACCURATE (real pairs)\n",
              "Exactly N hypotheses for rcme (OpenCV's USAC cannot be held to N, see above), "
              "medians over every real run:\n",
              timing_table(rows_real, args.iterations)]
    if run.get("defaults"):
        lines += ["At each library's defaults: at most N = %d hypotheses, adaptive "
                  "termination at confidence %.2f (rcme: `exactIterations` false; OpenCV: "
                  "confidence %.2f), one call per real pair and method; the errors and rates "
                  "are of these calls:\n" % (DEFAULT_SETTINGS_N, methods.DEFAULT_CONFIDENCE,
                                             methods.DEFAULT_CONFIDENCE),
                  defaults_table(run["defaults"], real_datasets)]
    lines += ["### Plots (N = %d)\n" % N_max] + ["![%s](%s)\n" % (p, p) for p in png]
    path = os.path.join(args.out, "report.md")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return path, png


def confusion_section(run, names, real_datasets, N_max):
    """The confusion tables (report.CONFUSION_LEGEND): the targets' rates per suite, then every
    dataset and method, at exactly N_max hypotheses and at the libraries' adaptive defaults."""
    real = [r for r in run["real"] if r["N"] == N_max]
    pose = report._pose_datasets(run["real"])
    corridor_rows = [r for r in run["synthetic"] if r["N"] == N_max]
    hard_rows = run.get("hard") or []

    def suites(rows):
        return [("calibrated real pairs", [r for r in rows if r["dataset"] in pose]),
                ("F-only real pairs", [r for r in rows if r["dataset"] not in pose])]

    lines = ["## Confusion table: statuses against ground truth\n", report.CONFUSION_LEGEND
             + " Percentages of the runs of the row; caught and false alarms as the targets of "
             "issue 15 count them (a flag without a rejected model is in neither).\n",
             "### Summary, exactly N = %d hypotheses\n" % N_max,
             report.confusion_summary(suites(real) + [("corridor (synthetic)", corridor_rows),
                                                      ("hard cases (synthetic)", hard_rows),
                                                      ("all suites",
                                                       real + corridor_rows + hard_rows)],
                                      names)]
    defaults = run.get("defaults") or []
    corridor_adaptive = run.get("corridor_adaptive") or []
    hard_adaptive = run.get("hard_adaptive") or []
    if defaults:
        synthetic = [("corridor (synthetic)", corridor_adaptive),
                     ("hard cases (synthetic)", hard_adaptive)]
        lines += ["### Summary, adaptive termination (at most N = %d, confidence %.2f)\n" % (
            DEFAULT_SETTINGS_N, methods.DEFAULT_CONFIDENCE),
            report.confusion_summary(
                suites(defaults) + [s for s in synthetic if s[1]]
                + [("all suites", defaults + corridor_adaptive + hard_adaptive)],
                DEFAULT_SETTINGS_METHODS)]
    calibrated = [r for r in real if r["dataset"] in pose]
    calibrated_adaptive = [r for r in defaults if r["dataset"] in pose]
    pose_datasets = [d for d in real_datasets if d in pose]

    def per_dataset(rows):
        return [(d, [r for r in rows if r["dataset"] == d]) for d in pose_datasets] + [
            ("all calibrated pairs", rows)]

    lines += ["### Accuracy: AUC@%.0f on the calibrated real pairs\n" % report.AUC_LIMIT_DEG,
              "Mean over the runs of max(0, 1 - e / %.0f deg), e = max(rotation error, "
              "translation direction error); a run without a motion (a flag, no model) counts as "
              "an infinite error. Exactly N = %d: %d runs per rcme method (every seed), one per "
              "pair for the peers; adaptive: one run per pair.\n" % (
                  report.AUC_LIMIT_DEG, N_max,
                  sum(r["method"] == methods.DEFAULT_METHOD for r in calibrated)),
              report.auc_table([("exactly N = %d" % N_max, calibrated),
                                ("adaptive", calibrated_adaptive)], names) + "\n",
              "Per dataset, exactly N = %d:\n" % N_max,
              report.auc_table(per_dataset(calibrated), names) + "\n"]
    if calibrated_adaptive:
        lines += ["Per dataset, adaptive:\n",
                  report.auc_table(per_dataset(calibrated_adaptive),
                                   DEFAULT_SETTINGS_METHODS) + "\n"]
    if any(r["method"] == POSELIB for r in calibrated):
        lines += ["### Targets: AUC@%.0f of the default against PoseLib per dataset\n"
                  % report.AUC_LIMIT_DEG,
                  report.auc_targets([("exactly N = %d" % N_max, per_dataset(calibrated)),
                                      ("adaptive", per_dataset(calibrated_adaptive))],
                                     methods.DEFAULT_METHOD, POSELIB) + "\n"]
    lines += ["### Per dataset, exactly N = %d\n" % N_max,
              report.confusion_table(real, names, real_datasets)]
    if corridor_rows:
        corridor_sets = sorted({r["dataset"] for r in corridor_rows})
        lines += ["### Corridor, exactly N = %d\n" % N_max,
                  report.confusion_table(corridor_rows, names, corridor_sets)]
    if hard_rows:
        lines += ["### Hard cases, exactly N = %d\n" % N_max,
                  "`samples/benchmark/hard_cases.py`, deterministic per seed; the corridor case "
                  "runs N = 200 for every method (adaptive: at most 200), as issue 15 sets it. "
                  "Pure rotation and "
                  "all outliers have no translation to return: every returned motion is wrong "
                  "there, every flag a caught failure.\n",
                  report.confusion_table(hard_rows, names,
                                         sorted({r["dataset"] for r in hard_rows}))]
    if defaults:
        lines += ["### Per dataset, adaptive termination\n",
                  report.confusion_table(defaults, DEFAULT_SETTINGS_METHODS, real_datasets)]
    for title, rows in [("Corridor", corridor_adaptive), ("Hard cases", hard_adaptive)]:
        if rows:
            lines += ["### %s, adaptive termination\n" % title,
                      report.confusion_table(rows, DEFAULT_SETTINGS_METHODS,
                                             sorted({r["dataset"] for r in rows}))]
    return lines


DEFAULT_SETTINGS_N = 1000
POSELIB = "PoseLib relpose"  # the peer of issue 33's accuracy targets
DEFAULT_SETTINGS_METHODS = [m for m in [methods.DEFAULT_METHOD, "RCME", "Standard",
                                         "cv USAC_DEFAULT", "cv USAC_ACCURATE",
                                         "cv E USAC_MAGSAC", "PoseLib relpose"]
                            if m in methods.METHODS]


def run_defaults(task_pairs, sigma, label="defaults"):
    """The timed methods once per pair as a user calls them: adaptive termination. Synthetic
    pairs keep the sigma they were generated with."""
    rows = []
    progress = Progress(len(task_pairs) * len(DEFAULT_SETTINGS_METHODS), label)
    for pair in task_pairs:
        pair_sigma = pair.sigma if pair.sigma is not None else sigma
        pair_n = DEFAULT_SETTINGS_N if pair.iterations is None else pair.iterations
        for method in DEFAULT_SETTINGS_METHODS:
            row = evaluate.evaluate(method, pair, methods.Budget(pair_n, pair_sigma, 0,
                                                                 adaptive=True))
            if row is not None:
                rows.append(row)
            progress.step()
    return rows


def defaults_table(rows, datasets):
    out = []
    for dataset in datasets + ["all"]:
        subset = rows if dataset == "all" else [r for r in rows if r["dataset"] == dataset]
        line = [dataset]
        for method in DEFAULT_SETTINGS_METHODS:
            s = report.summarize([r for r in subset if r["method"] == method])
            line.append("%s ms, %s %% GT failure, %s %% degenerate" % (
                s["ms"], s["gt_fail"], s["degenerate"]))
        rcme_ms = [r["seconds"] for r in subset if r["method"] == "RCME"]
        cv_ms = [r["seconds"] for r in subset if r["method"] == "cv USAC_ACCURATE"]
        line.append("%.1f" % (np.median(rcme_ms) / np.median(cv_ms)) if rcme_ms and cv_ms
                    else "n/a")
        out.append(line)
    return report._table(["dataset"] + ["%s (median)" % m for m in DEFAULT_SETTINGS_METHODS]
                         + ["RCME / USAC_ACCURATE"], out)


def timing_table(rows, iterations):
    out = []
    for N in iterations:
        rcme_ms = [1000 * r["seconds"] for r in rows if r["N"] == N and r["method"] == "RCME"]
        cv_ms = [1000 * r["seconds"] for r in rows
                 if r["N"] == N and r["method"] == "cv USAC_ACCURATE"]
        if rcme_ms and cv_ms:
            out.append([N, "%.2f" % np.median(rcme_ms), "%.2f" % np.median(cv_ms),
                        "%.1f" % (np.median(rcme_ms) / np.median(cv_ms))])
    return report._table(["N", "RCME median ms", "USAC_ACCURATE median ms", "ratio"], out)


def check(args, rows_real, path, png, bound):
    """The --check-rcme-gt-failure test: fails loudly, never silently."""
    problems = []
    for f in [path] + [os.path.join(args.out, p) for p in png]:
        if not os.path.isfile(f) or os.path.getsize(f) == 0:
            problems.append("missing output %s" % f)
        elif f.endswith(".png") and cv2.imread(f) is None:
            problems.append("unreadable PNG %s" % f)
    if sorted(png) != sorted(PLOT_FILES):
        problems.append("expected the plots %s, got %s" % (PLOT_FILES, png))
    present = {r["method"] for r in rows_real}
    problems += ["method %s has no result on the real pairs" % m
                 for m in methods.METHODS if m not in present]
    pose = [r for r in rows_real if r["method"] == "RCME"
            and r["dataset"] in report._pose_datasets(rows_real)]
    rate = 100.0 * sum(r.get("gt_fail", False) for r in pose) / max(len(pose), 1)
    if not pose:
        problems.append("no RCME run on a pair with a ground-truth pose")
    elif rate > bound:
        problems.append("RCME's GT failure rate on the real pairs is %.1f %% > %.1f %%" % (
            rate, bound))
    print("check: RCME GT failure on %d real runs with a pose: %.1f %%" % (len(pose), rate))
    for p in problems:
        print("check FAILED: " + p)
    return not problems


def run_sparse(args, matcher, dense_pairs):
    """The sparse-pairs suite: (pairs, runs at exactly the largest N, adaptive runs)."""
    sequences, _ = datasets.load_all(args.data)
    suite = sparse_pairs.sparse_pairs(sequences, dense_pairs, matcher, args.quick)
    sys.stderr.write("sparse pairs: %d\n" % len(suite))
    exact = run_all(suite, [max(args.iterations)], args.seeds, args.sigma, "sparse")
    return suite, exact, run_defaults(suite, args.sigma, "sparse, adaptive")


def sparse_counts(rows, method):
    """(right, undetected, wrong) shares of the judged runs of `method`: returned and right,
    returned and wrong, and wrong whether flagged or not (a peer's wrong answers)."""
    counts = report.confusion_counts(report._select(rows, method=method))
    judged = sum(counts.values()) - counts["unjudgeable"]
    if not judged:
        return None
    return (counts["returned_right"] / judged, counts["returned_wrong"] / judged,
            (counts["returned_wrong"] + counts["flagged_wrong"]) / judged)


def write_sparse_report(args, run, command):
    """<out>/sparse_pairs.md: the suite's pairs, confusion tables, AUC@10 and its targets."""
    rows_exact, rows_adaptive = run["sparse"], run["sparse_adaptive"]
    names = list(methods.METHODS)
    datasets_seen = []
    for pair in run["sparse_pairs"]:
        if pair["dataset"] not in datasets_seen:
            datasets_seen.append(pair["dataset"])
    N = max(args.iterations)
    lines = ["# Benchmark: the sparse-pairs suite\n",
             "Generated by `samples/benchmark/run_benchmark.py`; do not edit by hand.\n",
             "- Command: `%s`" % command,
             "- Date: %s; %s" % (datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"),
                                 machine_description()),
             "- Settings as the main suite's (report.md): noise sigma %.2f px, inlier threshold "
             "%.2f px for every method, exactly N = %d (%d seed(s) per pair for rcme's "
             "methods, one run for the peers) and adaptive termination (at most N = %d, "
             "confidence %.2f, no minimum number of samples).\n" % (
                 args.sigma, methods.Budget(N, args.sigma, 0).threshold, N, args.seeds,
                 DEFAULT_SETTINGS_N, methods.DEFAULT_CONFIDENCE),
             " ".join(sparse_pairs.__doc__.split()) + "\n"]
    table = []
    for name in datasets_seen:
        counts = [p["matches"] for p in run["sparse_pairs"] if p["dataset"] == name]
        table.append([name, len(counts), "%d / %d / %d" % (min(counts), np.median(counts),
                                                           max(counts))])
    lines += ["### Pairs\n", report._table(["dataset", "pairs", "matches (min / median / max)"],
                                           table) + "\n"]
    groups = lambda rows: [(name, [r for r in rows if r["dataset"] == name])
                           for name in datasets_seen] + [("all sparse pairs", rows)]
    lines += ["### Confusion table, exactly N = %d\n" % N, report.CONFUSION_LEGEND + "\n",
              report.confusion_summary(groups(rows_exact), names) + "\n",
              "### Confusion table, adaptive termination\n",
              report.confusion_summary(groups(rows_adaptive), DEFAULT_SETTINGS_METHODS) + "\n",
              "### Accuracy: AUC@%.0f\n" % report.AUC_LIMIT_DEG,
              "As report.md's: a run without a motion counts as an infinite error.\n",
              "Exactly N = %d:\n" % N, report.auc_table(groups(rows_exact), names) + "\n",
              "Adaptive:\n", report.auc_table(groups(rows_adaptive), DEFAULT_SETTINGS_METHODS)
              + "\n"]
    targets = []
    for label, rows in (("exactly N = %d" % N, rows_exact), ("adaptive", rows_adaptive)):
        ours = sparse_counts(rows, methods.DEFAULT_METHOD)
        peer = sparse_counts(rows, POSELIB)
        if ours is None or peer is None:
            continue
        targets.append([label, "right %.1f %% >= PoseLib's %.1f %%" % (100 * ours[0],
                                                                     100 * peer[0]),
                        "met" if ours[0] >= peer[0] else "**not met**"])
        targets.append([label, "undetected %.1f %% <= a third of PoseLib's wrong %.1f %%" % (
            100 * ours[1], 100 * peer[2]), "met" if ours[1] <= peer[2] / 3 else "**not met**"])
    if targets:
        lines += ["### Targets: the default against PoseLib (shares of the judged runs)\n",
                  report._table(["runs", "target", ""], targets) + "\n"]
    if any(r["method"] == POSELIB for r in rows_exact):
        lines += ["AUC@%.0f per dataset:\n" % report.AUC_LIMIT_DEG,
                  report.auc_targets([("exactly N = %d" % N, groups(rows_exact)),
                                      ("adaptive", groups(rows_adaptive))],
                                     methods.DEFAULT_METHOD, POSELIB) + "\n"]
    path = os.path.join(args.out, SPARSE_REPORT)
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return path


def sparse_record(suite, exact, adaptive):
    return {"sparse": exact, "sparse_adaptive": adaptive,
            "sparse_pairs": [{"dataset": p.dataset, "name": p.name,
                              "matches": len(p.points1)} for p in suite]}


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    runner = ("samples/benchmark/with_poselib.sh " if methods.poselib is not None
              else "PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/run_benchmark.py ")
    command = runner + " ".join(sys.argv[1:] if argv is None else argv)
    start = time.time()
    # the record of the run, so that --report-only can redraw the report without rerunning
    record_path = os.path.join(args.cache, "run_%s.json" % ("quick" if args.quick else "full"))
    if args.sparse_only:
        if not any(datasets.load_all(args.data)):
            print("skipped: no data under %s (pass --data; ../shared/data/README.md)" % args.data)
            return EXIT_SKIPPED
        os.makedirs(args.out, exist_ok=True)
        path = os.path.join(args.out, SPARSE_REPORT)
        if os.path.exists(path):  # a stale report must not pass
            os.remove(path)
        matcher = matching.Matcher(args.cache)
        dense, _ = real_pairs(args, matcher)
        run = sparse_record(*run_sparse(args, matcher, dense))
        path = write_sparse_report(args, run, command.strip())
        missing = [m for m in methods.METHODS
                   if not any(r["method"] == m for r in run["sparse"])]
        print("wrote %s: %d pairs in %.0f s%s" % (
            path, len(run["sparse_pairs"]), time.time() - start,
            "; no run of " + ", ".join(missing) if missing else ""))
        return 0 if run["sparse_pairs"] and not missing else 1
    if args.report_only or args.hard_only:
        with open(record_path) as f:
            run = json.load(f)
        if args.hard_only:
            hard = hard_cases.hard_case_pairs(args.hard_seeds)
            run["hard"] = run_all(hard, [max(args.iterations)], 1, args.sigma, "hard cases")
            run["hard_adaptive"] = run_defaults(hard, args.sigma, "hard, adaptive")
            with open(record_path, "w") as f:
                json.dump(run, f)
    else:
        if not any(datasets.load_all(args.data)):
            print("skipped: no data under %s (pass --data; ../shared/data/README.md)" % args.data)
            return EXIT_SKIPPED
        for name in REPORT_FILES:  # a stale report must not pass the check
            if os.path.exists(os.path.join(args.out, name)):
                os.remove(os.path.join(args.out, name))
        matcher = matching.Matcher(args.cache)
        task_pairs, notes = real_pairs(args, matcher)
        corridor_scenes = corridor_pairs(args)
        rows_synthetic = run_all(corridor_scenes, [max(args.iterations)], 1, args.sigma,
                                 "corridor")
        rows_real = run_all(task_pairs, args.iterations, args.seeds, args.sigma, "real")
        hard_scenes = hard_cases.hard_case_pairs(args.hard_seeds)
        rows_hard = run_all(hard_scenes, [max(args.iterations)], 1, args.sigma, "hard cases")
        rows_defaults = run_defaults(task_pairs, args.sigma)
        sparse = sparse_record(*run_sparse(args, matcher, task_pairs))
        run = {"synthetic": rows_synthetic, "real": rows_real, "defaults": rows_defaults,
               "hard": rows_hard,
               "corridor_adaptive": run_defaults(corridor_scenes, args.sigma, "corridor, adaptive"),
               "hard_adaptive": run_defaults(hard_scenes, args.sigma, "hard, adaptive"),
               "notes": notes,
               "elapsed": time.time() - start, "command": command.strip(),
               "date": datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"),
               "machine": machine_description()}
        run.update(sparse)
        with open(record_path, "w") as f:
            json.dump(run, f)
    path, png = write_report(args, run)
    if "sparse" in run:
        write_sparse_report(args, run, run.get("command", command.strip()))
    print("wrote %s and %d plots in %.0f s" % (path, len(png), time.time() - start))
    if args.check_rcme_gt_failure is not None:
        return 0 if check(args, run["real"], path, png, args.check_rcme_gt_failure) else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
