"""The VO-front-end suite (issue 39): every consecutive pair (i, i+1) and (i, i+2) of the KITTI
sequences in ../shared/data, with the tracks a classic monocular VO front end feeds its
estimator (FAST corners tracked by pyramidal KLT, kept when the backward track returns within
FB_MAX_PX), and ORB matches as a second input; plus pairs without motion: a frame with itself
("static") and with a stale copy of itself (a new exposure of a camera standing still: the same
frame plus sensor noise), and that stale copy with the next frame ("after stale").

Every method gets the same tracks, threshold (1.96 sigma), confidence and at most N hypotheses
with its own adaptive termination (methods.Budget(adaptive=True)), one thread; the time is the
estimator call only (for OpenCV: findEssentialMat + recoverPose). Judged as the benchmark
judges (evaluate.py, report.py): right when rotation <= 5 deg and translation direction <= 15 deg.

    PYTHONPATH=build/python python3 samples/benchmark/vo_front_end.py [--quick]
    samples/benchmark/with_poselib.sh --vo-front-end            (with PoseLib as a peer)

Writes doc/benchmark/vo_front_end.md (or --out)."""
import argparse
import os
import sys
from dataclasses import dataclass

import numpy as np
import cv2

import datasets
import evaluate
import methods
import report
from pairs import Pair

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SEQUENCES = [("KITTI 01", "kitti_odometry_01_frames000-050"),
             ("KITTI 06", "kitti_odometry_06_frames000-050")]

# The front end of OpenCV-based monocular VO examples: FAST (threshold 20, non-maximum
# suppression), cv2.calcOpticalFlowPyrLK with a 21x21 window, 3 pyramid levels, 30 iterations or
# 0.01 px, and the forward-backward check of tracking code (the backward track within 1 px).
FAST_THRESHOLD = 20
LK_PARAMS = dict(winSize=(21, 21), maxLevel=3,
                 criteria=(cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 30, 0.01))
FB_MAX_PX = 1.0
ORB_FEATURES = 3000
STALE_NOISE_GREY = 2.0  # sensor noise of the stale copy (grey levels, std)
SPECIAL_EVERY = 5       # frames 0, 5, 10, ... get the static / stale pairs

METHODS = [methods.DEFAULT_METHOD, "cv E RANSAC", "cv E USAC_MAGSAC", "PoseLib relpose"]
N = 1000


@dataclass
class Tracks:
    """Correspondences of a pair and the forward-backward error of each (px; KLT, zeros for
    ORB), which the analysis (vo_front_end_why.py) reads."""
    p1: np.ndarray
    p2: np.ndarray
    fb_error: np.ndarray


def klt_tracks(image1, image2):
    """FAST corners of image1 tracked into image2 and back; kept when both tracks converge and
    the backward track ends within FB_MAX_PX of the corner."""
    fast = cv2.FastFeatureDetector_create(FAST_THRESHOLD, True)
    p1 = cv2.KeyPoint_convert(fast.detect(image1)).reshape(-1, 1, 2).astype(np.float32)
    if len(p1) == 0:
        return Tracks(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    p2, st, _ = cv2.calcOpticalFlowPyrLK(image1, image2, p1, None, **LK_PARAMS)
    back, st_back, _ = cv2.calcOpticalFlowPyrLK(image2, image1, p2, None, **LK_PARAMS)
    fb = np.linalg.norm((back - p1).reshape(-1, 2), axis=1)
    h, w = image2.shape[:2]
    q = p2.reshape(-1, 2)
    keep = ((st.ravel() == 1) & (st_back.ravel() == 1) & (fb < FB_MAX_PX)
            & (q[:, 0] >= 0) & (q[:, 1] >= 0) & (q[:, 0] < w) & (q[:, 1] < h))
    return Tracks(p1.reshape(-1, 2)[keep].astype(np.float64), q[keep].astype(np.float64),
                  fb[keep])


def orb_matches(image1, image2):
    """ORB features matched by Hamming distance with the cross check (OpenCV's tutorials)."""
    orb = cv2.ORB_create(ORB_FEATURES)
    k1, d1 = orb.detectAndCompute(image1, None)
    k2, d2 = orb.detectAndCompute(image2, None)
    if d1 is None or d2 is None:
        return Tracks(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d1, d2)
    p1 = np.array([k1[m.queryIdx].pt for m in matches], np.float64).reshape(-1, 2)
    p2 = np.array([k2[m.trainIdx].pt for m in matches], np.float64).reshape(-1, 2)
    return Tracks(p1, p2, np.zeros(len(p1)))


INPUTS = {"KLT": klt_tracks, "ORB": orb_matches}


def stale_copy(image, index):
    """A new exposure of a camera standing still: the frame plus Gaussian noise (seeded)."""
    noise = np.random.default_rng(index).normal(0.0, STALE_NOISE_GREY, image.shape)
    return np.clip(image.astype(np.float64) + noise, 0, 255).astype(np.uint8)


def vo_pairs(sequence, label, frames=None, inputs=("KLT",), first=0):
    """[(kind, Pair, Tracks)] of frames first, first + 1, ... (`frames` of them, all by default):
    kind is "i+1", "i+2", "static", "stale" or "after stale"; the pair's dataset is
    "<sequence> <input>"."""
    end = len(sequence.images) if frames is None else min(first + frames, len(sequence.images))
    images = {i: cv2.imread(sequence.images[i], cv2.IMREAD_GRAYSCALE) for i in range(first, end)}
    K = sequence.K
    plan = []  # (kind, i, j, first image, second image)
    for step in (1, 2):
        plan += [("i+%d" % step, i, i + step, images[i], images[i + step])
                 for i in range(first, end - step)]
    for i in range(first, end - 1):
        if i % SPECIAL_EVERY:
            continue
        stale = stale_copy(images[i], i)
        plan += [("static", i, i, images[i], images[i]), ("stale", i, i, images[i], stale),
                 ("after stale", i, i + 1, stale, images[i + 1])]
    out = []
    for kind, i, j, a, b in plan:
        if i == j:
            R, t = np.eye(3), np.zeros(3)
        else:
            R, t, _ = sequence.relative_motion(i, j)
        for name in inputs:
            tracks = INPUTS[name](a, b)
            pair = Pair("%s %s" % (label, name), "%s %d-%d" % (kind, i, j), tracks.p1, tracks.p2,
                        K, R, np.asarray(t, np.float64).ravel())
            out.append((kind, pair, tracks))
    return out


def load_sequences(data_dir):
    out = []
    for label, folder in SEQUENCES:
        path = os.path.join(data_dir, folder)
        if os.path.isdir(path):
            out.append((label, datasets.kitti_sequence(path, label)))
    return out


def run(task, method_names, sigma):
    """A row per (pair, method) from evaluate.evaluate, with the pair's kind; methods interleave
    on each pair so that the machine's load falls on all of them alike."""
    rows = []
    for kind, pair, _ in task:
        for method in method_names:
            row = evaluate.evaluate(method, pair, methods.Budget(N, sigma, 0, adaptive=True))
            if row is not None:
                row["kind"] = kind
                rows.append(row)
    return rows


def run_other_states(task, sigma, states):
    """Rows of the default alone under other generator states than the suite's 0 (its answers
    on a pair can depend on the samples drawn), each labelled "rcme default, state k"."""
    rows = []
    for kind, pair, _ in task:
        for state in states:
            row = evaluate.evaluate(methods.DEFAULT_METHOD, pair,
                                    methods.Budget(N, sigma, state, adaptive=True))
            if row is not None:
                row["kind"] = kind
                row["method"] = "%s, state %d" % (methods.DEFAULT_METHOD, state)
                rows.append(row)
    return rows


def _state_lines(rows):
    names = sorted({r["method"] for r in rows})
    groups = []
    for d in sorted({r["dataset"] for r in rows}):
        for label, kinds in (("moving", ("i+1", "i+2", "after stale")),
                             ("static / stale", ("static", "stale"))):
            subset = [r for r in rows if r["dataset"] == d and r["kind"] in kinds]
            if subset:
                groups.append(("%s %s" % (d, label), subset))
    wrong = [r for r in rows if r["ok"] and r.get("gt_fail")]
    return report.confusion_summary(groups, names) + "\n\n" + (
        _wrong_lines(rows, names) if wrong else
        "No wrong motion returned with success under these states.")


def _time_lines(rows, method_names, groups):
    """Median ms per pair of each method, and the median per-pair ratio to cv E RANSAC."""
    lines = []
    for label, subset in groups:
        base = {r["pair"]: r["seconds"] for r in subset if r["method"] == "cv E RANSAC"}
        for method in method_names:
            mine = [r for r in subset if r["method"] == method]
            if not mine:
                continue
            ratios = [r["seconds"] / base[r["pair"]] for r in mine if base.get(r["pair"])]
            lines.append([label, method, len(mine),
                          "%.2f" % (1e3 * np.median([r["seconds"] for r in mine])),
                          "%.2f" % np.median(ratios) if ratios else "n/a"])
    return report._table(["pairs", "method", "runs", "median ms per pair",
                          "median ratio to cv E RANSAC (same pair)"], lines)


def write_report(rows, method_names, path, task, argv, sigma, load, state_rows=()):
    datasets_ = sorted({r["dataset"] for r in rows})
    moving = [r for r in rows if r["kind"] in ("i+1", "i+2", "after stale")]
    groups = []
    for d in datasets_:
        for kinds in (("i+1",), ("i+2",), ("after stale",), ("static", "stale")):
            subset = [r for r in rows if r["dataset"] == d and r["kind"] in kinds]
            if subset:
                groups.append(("%s %s" % (d, " / ".join(kinds)), subset))
    tracks = {}
    for kind, pair, _ in task:
        tracks.setdefault((pair.dataset, kind), []).append(len(pair.points1))
    track_lines = [[d, k, len(v), int(np.median(v)), int(np.min(v)), int(np.max(v))]
                   for (d, k), v in sorted(tracks.items())]
    auc_groups = [(label, [r for r in subset if r["kind"] not in ("static", "stale")])
                  for label, subset in groups if "static" not in label]
    text = [
        "# VO front end: consecutive KITTI pairs, KLT tracks (issue 39)\n",
        "Written by `samples/benchmark/vo_front_end.py %s`; %s.\n" % (
            " ".join(argv), _machine()),
        __doc__.split("\n\n")[0].replace("\n", " ") + "\n",
        "Settings: threshold %.2f px (sigma %.2f), confidence %.2f, at most N = %d hypotheses, "
        "each method's own adaptive termination; rcme: `rcme.Params()` (the defaults) with these; "
        "OpenCV %s: `findEssentialMat(K, method, confidence, threshold, N)` + `recoverPose`; "
        "PoseLib: `estimate_relative_pose` (5-point, LO, bundle adjustment). FAST threshold %d, "
        "KLT %s, forward-backward <= %.1f px; ORB %d features, cross-checked. Static / stale "
        "pairs: every %dth frame; their truth has no translation, so any returned motion is "
        "wrong and any flag is caught.\n" % (
            methods.Budget(N, sigma, 0).threshold, sigma,
            methods.DEFAULT_CONFIDENCE, N, cv2.__version__, FAST_THRESHOLD,
            "21x21, 3 levels", FB_MAX_PX, ORB_FEATURES, SPECIAL_EVERY),
        "## Correspondences per pair\n",
        report._table(["input", "pairs", "count", "median", "min", "max"], track_lines),
        "\n## Confusion\n",
        report.CONFUSION_LEGEND + "\n",
        report.confusion_summary(groups, method_names),
        "\n## AUC@10 (moving pairs)\n",
        "Mean over the runs of max(0, 1 - max(rotation, translation error) / 10 deg); a run "
        "without a motion scores 0.\n",
        report.auc_table(auc_groups, method_names),
        "\n## Time per pair (estimator call only, one thread)\n",
        "Load average at the start of the run: %.2f (1 min) on %d logical CPUs; absolute times "
        "depend on it, the ratios of calls interleaved on the same pair less so.\n"
        % (load, os.cpu_count() or 0),
        _time_lines(moving, method_names,
                    [(d, [r for r in moving if r["dataset"] == d]) for d in datasets_]),
        "\n## Pairs returned wrong with success\n",
        _wrong_lines(rows, method_names),
    ]
    if state_rows:
        text += [
            "\n## The default under other generator states\n",
            "The same pairs and settings, `Params.randomGeneratorState` k instead of 0 (the "
            "tables above): the samples the loop draws change, so may the answer.\n",
            _state_lines(state_rows),
        ]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(text) + "\n")


def _wrong_lines(rows, method_names):
    lines = []
    for d in sorted({r["dataset"] for r in rows}):
        for method in method_names:
            bad = [r for r in rows if r["dataset"] == d and r["method"] == method and r["ok"]
                   and r.get("gt_fail")]
            if bad:
                lines.append([d, method, len(bad), ", ".join(
                    "%s (%s)" % (r["pair"], "%.0f deg" % r["trans"] if "trans" in r else
                                 "no motion") for r in bad)])
    return report._table(["input", "method", "count", "pairs (translation error)"], lines)


def _machine():
    from run_benchmark import machine_description
    return machine_description()


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(REPO_ROOT, "..", "shared", "data"))
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, "doc", "benchmark",
                                                  "vo_front_end.md"))
    ap.add_argument("--sigma", type=float, default=1.0, help="noise (px); threshold 1.96 sigma")
    ap.add_argument("--inputs", default="KLT,ORB", help="KLT, ORB or both (comma-separated)")
    ap.add_argument("--quick", action="store_true",
                    help="the first 8 frames of each sequence (the ctest smoke run)")
    ap.add_argument("--sequence", choices=[label for label, _ in SEQUENCES],
                    help="only this sequence")
    ap.add_argument("--first-frame", type=int, default=0, help="frames from this one on")
    ap.add_argument("--frames", type=int, help="this many frames (default: all, 8 with --quick)")
    ap.add_argument("--methods", help="comma-separated subset of " + ", ".join(METHODS))
    ap.add_argument("--other-states", default="1,2,3",
                    help="generator states the default runs under too (comma-separated; "
                         "empty: none)")
    ap.add_argument("--max-wrong-with-success", type=int,
                    help="exit with 1 when the default returns more wrong motions with success")
    args = ap.parse_args(argv)
    chosen = METHODS if args.methods is None else args.methods.split(",")
    unknown = [m for m in chosen if m not in METHODS]
    if unknown:
        ap.error("--methods: unknown %s (the suite's: %s)" % (", ".join(unknown),
                                                              ", ".join(METHODS)))
    try:
        states = [int(k) for k in args.other_states.split(",") if k.strip()]
    except ValueError:
        ap.error("--other-states: comma-separated integers, not %r" % args.other_states)
    if args.first_frame < 0 or (args.frames is not None and args.frames < 2):
        ap.error("--first-frame must be >= 0 and --frames >= 2")
    cv2.setNumThreads(1)
    sequences = [s for s in load_sequences(args.data)
                 if args.sequence is None or s[0] == args.sequence]
    if not sequences:
        print("no KITTI sequence under %s" % args.data)
        return 77
    names = [m for m in chosen if m in methods.METHODS]
    inputs = args.inputs.split(",")
    frames = args.frames if args.frames is not None else (8 if args.quick else None)
    task = []
    for label, sequence in sequences:
        task += vo_pairs(sequence, label, frames, inputs, args.first_frame)
    load = os.getloadavg()[0]
    rows = run(task, names, args.sigma)
    state_rows = (run_other_states(task, args.sigma, states)
                  if methods.DEFAULT_METHOD in names else [])
    write_report(rows, names, args.out, task, argv, args.sigma, load, state_rows)
    print(open(args.out).read())
    complete = all(any(r["method"] == m and r["pair"] == p.name and r["dataset"] == p.dataset
                       for r in rows) for _, p, _ in task for m in names)
    if not complete:
        return 1
    wrong = [r for r in rows if r["method"] == methods.DEFAULT_METHOD and r["ok"]
             and r.get("gt_fail")]
    if args.max_wrong_with_success is not None and len(wrong) > args.max_wrong_with_success:
        print("%s: %d wrong with success (at most %d): %s" % (
            methods.DEFAULT_METHOD, len(wrong), args.max_wrong_with_success,
            ", ".join("%s %s" % (r["dataset"], r["pair"]) for r in wrong)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
