#!/usr/bin/python3
"""The F-only suite (issue 38): findFundamentalMat's callers without a camera matrix. Four
parts, no K for any method:

- given rows: every MAGSAC/AdelaideRMF pair of ../shared/data from its *_pts.txt rows as given
  (the vpts pairs: the annotated matches among the other putative matches the dataset ships;
  AdelaideRMF: every labelled row), judged by the annotated matches (vpts) or the labels >= 1;
  the pairs whose unlabelled rows are another pair's (datasets.rows_of_another_pair) are a part
  of their own;
- SIFT: the vpts pairs matched with SIFT as the main benchmark matches them (matching.py);
- synthetic hard cases (hard_cases.f_only_hard_case_pairs): few true matches among many, 40-80
  points, a plane with a few points off it, clustered matches.

Every method gets the same correspondences, threshold (1.96 sigma, sigma 1 px), confidence 0.99
and at most N = 1000 hypotheses with its own adaptive termination, seed 0, one call per pair
(for the time ratio of rcme's default to USAC_ACCURATE, the fastest of --time-repeats calls each).
A returned F is right when the RMS Sampson distance of the true matches under it is at most
metrics.F_FAILURE_PX; a flag (rcme's statuses other than success) is judged through
Report.rejectedF. Pairs whose true matches cannot tell one epipole from another
(metrics.epipole_blind) are counted apart.

    samples/benchmark/with_poselib.sh --f-only [--quick] [--out FILE]
    PYTHONPATH=build/python python3 samples/benchmark/f_only.py   (without PoseLib)
    f_only.py --parts given --max-wrong-with-success 0   (the given rows; exit 1 on a wrong F
                                                           returned with success)

Writes a markdown report (default build/f_only.md) and prints the targets' figures."""
import json
import os
import sys

import numpy as np

import datasets
import evaluate
import hard_cases
import matching
import methods
import pairs
import report

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
METHODS = [m for m in [methods.DEFAULT_METHOD, "cv FM_RANSAC", "cv FM_LMEDS", "cv USAC_MAGSAC",
                       "cv USAC_ACCURATE", "PoseLib F"]
           if m in methods.METHODS or m in methods.F_ONLY_METHODS]
REFERENCE = "cv USAC_ACCURATE"  # the peer the targets name
N = 1000
SIGMA = 1.0
EXIT_SKIPPED = 77
# The given pairs whose unlabelled rows belong to another image pair: their input holds nothing
# of their own geometry but the few annotated rows, so every estimator returns the other pair's
# F; counted apart from the given rows, with the reason.
BORROWED = "given rows of another pair"
QUICK_PAIRS = {"magsac/Brussels", "magsac/corr", "magsac/booksh", "adelaide/bonython",
               "adelaide/library"}
# --parts: the short name of each part, in the report's order.
PARTS = {"given": "given rows", "borrowed": BORROWED, "sift": "SIFT (vpts pairs)",
         "synthetic": "synthetic hard cases"}


def parse_args(argv):
    ap = matching.benchmark_arguments(__doc__, REPO_ROOT,
                                      os.path.join(REPO_ROOT, "build", "f_only.md"))
    ap.add_argument("--hard-seeds", type=int, default=10)
    ap.add_argument("--quick", action="store_true",
                    help="five given pairs, two SIFT pairs, one seed of the hard cases")
    ap.add_argument("--parts", default=",".join(PARTS),
                    help="comma-separated subset of " + ", ".join(PARTS))
    ap.add_argument("--time-repeats", type=int, default=1,
                    help="calls of rcme's default and %s per pair for the time ratio, the "
                         "fastest counted (the outcome is the first call's; every call with the "
                         "same seed returns the same)" % REFERENCE)
    ap.add_argument("--max-wrong-with-success", type=int,
                    help="exit with 1 when the default returns more wrong F with success on the "
                         "parts run, the given rows of another pair left out (no estimator can "
                         "find their own F in them)")
    args = ap.parse_args(argv)
    args.parts = args.parts.split(",")
    unknown = [p for p in args.parts if p not in PARTS]
    if unknown:
        ap.error("--parts: unknown %s; choose among %s" % (", ".join(unknown), ", ".join(PARTS)))
    if args.time_repeats < 1:
        ap.error("--time-repeats: at least 1, got %d" % args.time_repeats)
    if args.quick:
        args.hard_seeds = 1
    return args


def suites(args):
    """(suite name, [Pair]) for the parts of args.parts, and the given pairs whose unlabelled rows
    are another pair's (datasets.rows_of_another_pair: name -> owner and shares), a part of their
    own; None when the data folder is missing."""
    folder = os.path.join(args.data, "magsac_fundamental_pairs")
    if not os.path.isdir(folder):
        return None
    raw = datasets.magsac_pairs(folder)
    given = datasets.magsac_given_pairs(folder) + [p for p in raw if not p.images]
    # found on every pair, so that --quick's few pairs are judged as in the full run
    borrowed = datasets.rows_of_another_pair(given, methods.Budget(N, SIGMA, 0).threshold)
    sift = [p for p in raw if p.images]
    if args.quick:
        given = [p for p in given if p.name in QUICK_PAIRS]
        sift = [p for p in sift if p.name in QUICK_PAIRS][:2]
    matcher = matching.Matcher(args.cache)
    # each part made only when it runs: the SIFT part matches images when the cache lacks them
    make = {"given": lambda: pairs.labelled_pairs([p for p in given if p.name not in borrowed],
                                                  matcher),
            "borrowed": lambda: pairs.labelled_pairs([p for p in given if p.name in borrowed],
                                                     matcher),
            "sift": lambda: pairs.labelled_pairs(sift, matcher),
            "synthetic": lambda: hard_cases.f_only_hard_case_pairs(args.hard_seeds)}
    return [(PARTS[part], make[part]()) for part in PARTS if part in args.parts], borrowed


def run_suite(name, task_pairs, time_repeats=1):
    rows = []
    progress_total = len(task_pairs) * len(METHODS)
    for k, pair in enumerate(task_pairs):
        for method in METHODS:
            budget = methods.Budget(N, pair.sigma if pair.sigma is not None else SIGMA, 0,
                                    adaptive=True)
            row = evaluate.evaluate(method, pair, budget)
            if method in (methods.DEFAULT_METHOD, REFERENCE):
                for _ in range(time_repeats - 1):
                    row["seconds"] = min(row["seconds"],
                                         evaluate.evaluate(method, pair, budget)["seconds"])
            row["suite"] = name
            rows.append(row)
        sys.stderr.write("\r%s: %d/%d " % (name, (k + 1) * len(METHODS), progress_total))
    sys.stderr.write("\n")
    return rows


def targets(rows):
    """The issue's three figures for rcme's default against USAC_ACCURATE on these rows, and the
    median over the pairs of the per-pair time ratio (the two calls run one after the other)."""
    mine = report.confusion_counts([r for r in rows if r["method"] == methods.DEFAULT_METHOD])
    peer = report.confusion_counts([r for r in rows if r["method"] == REFERENCE])
    right = mine["returned_right"] + mine["flagged_right"]
    peer_wrong = peer["returned_wrong"]
    seconds = {}
    for r in rows:
        if r["method"] in (methods.DEFAULT_METHOD, REFERENCE):
            seconds.setdefault(r["pair"], {})[r["method"]] = r["seconds"]
    ratios = [s[methods.DEFAULT_METHOD] / s[REFERENCE] for s in seconds.values()
              if len(s) == 2 and s[REFERENCE] > 0]
    return {
        "undetected": mine["returned_wrong"], "reference wrong": peer_wrong,
        "undetected met": 3 * mine["returned_wrong"] <= peer_wrong,
        "false alarms": mine["flagged_right"], "right": right,
        "false alarms met": mine["flagged_right"] <= 0.02 * right,
        "returned right": mine["returned_right"], "reference right": peer["returned_right"],
        "right met": mine["returned_right"] >= peer["returned_right"],
        "time ratio": float(np.median(ratios)) if ratios else float("nan"),
    }


def targets_table(groups):
    lines = []
    for label, rows in groups:
        t = targets(rows)
        lines.append([label, "%d (%s)" % (t["undetected"], "met" if t["undetected met"] else
                                          "not met"),
                      t["reference wrong"],
                      "%d of %d right (%s)" % (t["false alarms"], t["right"],
                                               "met" if t["false alarms met"] else "not met"),
                      "%d vs %d (%s)" % (t["returned right"], t["reference right"],
                                         "met" if t["right met"] else "not met"),
                      "%.2f" % t["time ratio"]])
    return report._table(["suite", "rcme default undetected (target: <= 1/3 of the next "
                          "column)", "%s wrong" % REFERENCE,
                          "false alarms (target: <= 2 % of right)",
                          "returned right: rcme default vs %s (target: >=)" % REFERENCE,
                          "time per call, median of per-pair ratios rcme / %s" % REFERENCE],
                         lines)


def per_pair_table(rows):
    """A row per pair: each method's RMS Sampson error of the true matches (px) under what it
    returned, or its status (a flag: the rejected F's error in brackets)."""
    names = []
    for r in rows:
        if r["pair"] not in names:
            names.append(r["pair"])
    lines = []
    for name in names:
        mine = [r for r in rows if r["pair"] == name]
        cells = []
        for method in METHODS:
            r = next((x for x in mine if x["method"] == method), None)
            if r is None:
                cells.append("n/a")
            elif r["ok"]:
                cells.append("%.1f" % r["f_err"] if "f_err" in r else "ok")
            elif r.get("flagged"):
                cells.append("%s (%s)" % (r["status"], "%.1f" % r["rejected_f_err"]
                                          if r.get("rejected_f_err") is not None else "-"))
            else:
                cells.append(r["status"])
        lines.append([name + (" (blind)" if mine[0]["unjudgeable"] else ""),
                      mine[0]["points"]] + cells)
    return report._table(["pair", "rows"] + METHODS, lines)


def borrowed_table(borrowed):
    lines = [[name, owner, "%.0f %%" % (100 * own), "%.0f %%" % (100 * theirs)]
             for name, (owner, own, theirs) in sorted(borrowed.items())]
    return report._table(["pair", "its unlabelled rows are, row for row, those of",
                          "share within the threshold of its own F",
                          "of the other pair's F"], lines)


def write_report(path, groups, command, borrowed):
    everything = [r for _, rows in groups for r in rows]
    lines = ["# F-only suite (issue 38)\n",
             "Generated by `samples/benchmark/f_only.py` (`%s`); see its docstring for the "
             "settings.\n" % command,
             "## Targets\n", targets_table(groups),
             "## %s\n" % BORROWED.capitalize(),
             "Found in the data (datasets.rows_of_another_pair): these pairs' input is their "
             "annotated rows among another image pair's matches, so an F of their own cannot be "
             "expected from it; they are counted apart from the given rows.\n",
             borrowed_table(borrowed),
             "## Confusion table\n",
             report.CONFUSION_LEGEND + "\n",
             report.confusion_summary(groups + [("all", everything)], METHODS),
             "## Per dataset\n",
             report.confusion_table(everything, METHODS,
                                    sorted({r["dataset"] for r in everything}))]
    for label, rows in groups:
        lines += ["## Per pair: %s\n" % label,
                  "RMS Sampson error (px) of the true matches under the returned F; a flag "
                  "shows the status and, in brackets, the rejected F's error.\n",
                  per_pair_table(rows)]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    found = suites(args)
    if found is None:
        print("skipped: no MAGSAC pairs under %s" % args.data)
        return EXIT_SKIPPED
    groups_pairs, borrowed = found
    groups = [(label, run_suite(label, task_pairs, args.time_repeats))
              for label, task_pairs in groups_pairs if task_pairs]
    command = " ".join(["f_only.py"] + (sys.argv[1:] if argv is None else argv))
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    write_report(args.out, groups, command, borrowed)
    with open(os.path.splitext(args.out)[0] + ".json", "w") as f:
        json.dump({label: rows for label, rows in groups}, f, default=float)
    print(targets_table(groups))
    problems = ["%s: no run of %s" % (label, m) for label, rows in groups for m in METHODS
                if not any(r["method"] == m for r in rows)]
    wrong = [r for label, rows in groups if label != BORROWED for r in rows
             if r["method"] == methods.DEFAULT_METHOD
             and report.confusion_cell(r) == "returned_wrong"]
    if args.max_wrong_with_success is not None and len(wrong) > args.max_wrong_with_success:
        problems.append("%s: %d wrong F with success (at most %d): %s" % (
            methods.DEFAULT_METHOD, len(wrong), args.max_wrong_with_success,
            ", ".join("%s %s" % (r["suite"], r["pair"]) for r in wrong)))
    for p in problems:
        print("FAILED: " + p)
    print("wrote %s" % args.out)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
