"""Tables (markdown) and plots of the benchmark rows."""
import os

import numpy as np

import metrics
import plots
from methods import DEGENERATE, PQI


def _pct(count, total):
    return "n/a" if total == 0 else "%.1f" % (100.0 * count / total)


def _median(values, fmt="%.2f"):
    values = [v for v in values if v is not None and np.isfinite(v)]
    return fmt % np.median(values) if values else "n/a"


def summarize(rows):
    """Aggregates of the rows of one method on one dataset (and N)."""
    ok = [r for r in rows if r["ok"]]
    has_gt = any("gt_fail" in r for r in rows)
    return {
        "runs": len(rows),
        "pqi": _pct(sum(r["status"] == PQI for r in rows), len(rows)),
        "degenerate": _pct(sum(r["status"] == DEGENERATE for r in rows), len(rows)),
        "no_model": _pct(sum(r["status"] not in ("ok", PQI, DEGENERATE) for r in rows),
                         len(rows)),
        "paper_fail": _pct(sum(r["paper_fail"] for r in ok), len(rows)),
        "gt_fail": _pct(sum(r.get("gt_fail", False) for r in ok), len(rows)) if has_gt
        else "n/a",
        "rot": _median([r.get("rot") for r in ok]),
        "trans": _median([r.get("trans") for r in ok]),
        "f_err": _median([r.get("f_err") for r in ok]),
        "precision": _median([r.get("precision") for r in ok], "%.3f"),
        "recall": _median([r.get("recall") for r in ok], "%.3f"),
        "ms": _median([1000.0 * r["seconds"] for r in rows]),
        "dq": _mean_std([r.get("dq") for r in ok]),
        "dt": _mean_std([r.get("dt") for r in ok]),
    }


def _mean_std(values):
    values = [v for v in values if v is not None]
    return "%.3f (%.3f)" % (np.mean(values), np.std(values)) if values else "n/a"


def _select(rows, **keys):
    return [r for r in rows if all(r[k] == v for k, v in keys.items())]


def _table(header, lines):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in line) + " |" for line in lines]
    return "\n".join(out) + "\n"


def synthetic_tables(rows, method_names):
    out = []
    for dataset in sorted({r["dataset"] for r in rows}):
        for N in sorted({r["N"] for r in rows}):
            subset = _select(rows, dataset=dataset, N=N)
            if not subset:
                continue
            scenes = len({r["pair"] for r in subset})
            out.append("**%s, N = %d, %d scenes**\n" % (dataset, N, scenes))
            lines = []
            for method in method_names:
                s = summarize(_select(subset, method=method))
                if s["runs"]:
                    lines.append([method, s["dq"], s["dt"], s["rot"], s["trans"], s["pqi"],
                                  s["degenerate"], s["no_model"], s["gt_fail"],
                                  s["precision"], s["recall"], s["ms"]])
            out.append(_table(["method", "dq mean (std)", "dt mean (std)", "median rot. deg",
                               "median transl. deg", "PQI %", "degenerate %", "no model %",
                               "GT failure %", "inlier precision", "inlier recall",
                               "median ms"], lines))
    return "\n".join(out)


def table_two(rows, method_names, datasets, N):
    """Table II style: a row per dataset, a PQI / degenerate / paper-failure / GT-failure cell
    per method (PQI counting every run without a model that is not degenerate)."""
    lines = []
    for dataset in datasets + ["all"]:
        subset = _select(rows, N=N) if dataset == "all" else _select(rows, N=N, dataset=dataset)
        pairs = len({r["pair"] for r in subset})
        line = ["%s (#%d)" % (dataset, pairs)]
        line += [_cell(_select(subset, method=method)) for method in method_names]
        lines.append(line)
    return _table(["dataset (#pairs)"] + method_names, lines)


CELL_LEGEND = "Each cell: PQI or no model % / degenerate % / failure % (paper metric) / GT " \
    "failure %."


def _cell(rows):
    """PQI or no model / degenerate / paper failure / GT failure, % of the rows."""
    s = summarize(rows)
    if not s["runs"]:
        return "n/a"
    declined = _pct(sum(r["status"] not in ("ok", DEGENERATE) for r in rows), s["runs"])
    return "%s / %s / %s / %s" % (declined, s["degenerate"], s["paper_fail"], s["gt_fail"])


def overview_table(rows, method_names, iterations):
    """All real pairs: a row per method, a Table II cell per N, and the median errors and time
    at the largest N."""
    N_max = max(iterations)
    lines = []
    for method in method_names:
        mine = _select(rows, method=method)
        s = summarize(_select(mine, N=N_max))
        lines.append([method] + [_cell(_select(mine, N=N)) for N in iterations]
                     + [s["rot"], s["trans"], s["f_err"], s["ms"]])
    return _table(["method"] + ["N = %d" % N for N in iterations]
                  + ["median rot. deg", "median transl. deg", "median F err. px",
                     "median ms"], lines)


def detail_table(rows, method_names, dataset, N):
    lines = []
    subset = _select(rows, N=N, dataset=dataset)
    for method in method_names:
        s = summarize(_select(subset, method=method))
        if s["runs"]:
            lines.append([method, s["runs"], s["pqi"], s["degenerate"], s["no_model"],
                          s["paper_fail"], s["gt_fail"], s["rot"], s["trans"], s["f_err"],
                          s["precision"], s["recall"], s["ms"]])
    return _table(["method", "runs", "PQI %", "degenerate %", "no model %", "failure % (paper)",
                   "GT failure %",
                   "median rot. deg", "median transl. deg", "median F err. px",
                   "inlier precision", "inlier recall", "median ms"], lines)


def write_plots(rows, method_names, datasets, out_dir, N):
    """cumulative_rotation.png (real pairs with a pose) and a bar chart per rate (GT failure,
    PQI, degenerate, paper failure) per dataset, all at the largest N. Returns the file names."""
    subset = _select(rows, N=N)
    errors = {}
    for method in method_names:
        mine = [r for r in _select(subset, method=method) if r["dataset"] in datasets]
        pose_rows = [r for r in mine if "rot" in r or not r["ok"]]
        pose_rows = [r for r in pose_rows if r["dataset"] in _pose_datasets(subset)]
        if pose_rows:
            errors[method] = [r.get("rot", np.inf) for r in pose_rows]
    names = []
    if errors:
        plots.cumulative_curves(os.path.join(out_dir, "cumulative_rotation.png"),
                                "Rotation error on the real pairs with ground truth, N = %d "
                                "(no model = infinite error)" % N, errors,
                                x_label="rotation error, degrees")
        names.append("cumulative_rotation.png")
    for key, file_name, label in [("gt_fail", "gt_failure_rates.png", "GT failure %"),
                                  ("pqi", "pqi_rates.png", "PQI %"),
                                  ("degenerate", "degenerate_rates.png", "degenerate %"),
                                  ("paper_fail", "paper_failure_rates.png",
                                   "failure % (paper metric)")]:
        values = []
        for dataset in datasets:
            line = []
            for method in method_names:
                s = summarize(_select(subset, dataset=dataset, method=method))
                value = s[key] if s["runs"] else "n/a"
                line.append(float(value) if value != "n/a" else np.nan)
            values.append(line)
        plots.grouped_bars(os.path.join(out_dir, file_name), "%s per dataset, N = %d" % (
            label, N), datasets, method_names, values, label)
        names.append(file_name)
    return names


def _pose_datasets(rows):
    return {r["dataset"] for r in rows if "rot" in r}


THRESHOLDS_TEXT = (
    "Failure (paper, Sec. V-C.1): n_I = points of the method's inlier set whose Huber-robust "
    "Sampson error is below tau^2 = sigma^2 chi2_2^-1(0.95) (tau = %.2f px at sigma 1) under "
    "the method's output; n_I* = the same after a Huber-robust Gold Standard MLE started from "
    "it (over R, t when K is known, over a rank-2 F otherwise); failure when n_I*/n_I <= %.1f. "
    "GT failure: rotation error > %.0f deg or translation direction error > %.0f deg (pairs with "
    "a pose), or RMS Sampson error of the true matches under the estimated F > %.0f px "
    "(F-only pairs). Both failure rates, PQI, degenerate and no model are %% of all runs; a run "
    "without a model is not a failure (as the paper's Table II). PQI: rcme declined (poor quality "
    "input); degenerate: rcme's degeneracy test (`Params::degeneracyTest`, on by default) found "
    "that a homography explains the inliers about as well as F; no model: OpenCV returned none "
    "(or too few points)." % (
        np.sqrt(metrics.CHI2_2_95), metrics.PAPER_KAPPA, metrics.ROTATION_FAILURE_DEG,
        metrics.TRANSLATION_FAILURE_DEG, metrics.F_FAILURE_PX))


# The confusion table: every run with ground truth in one cell. Right / wrong by
# metrics.pose_failure (pairs with a pose) or the true matches' RMS Sampson error (F-only);
# a flag (rcme's statuses other than success) is judged through Report.rejectedF/R/t.
CONFUSION_CELLS = [("returned_right", "returned & right"),
                   ("returned_wrong", "returned & wrong (undetected)"),
                   ("flagged_wrong", "flagged & wrong (caught)"),
                   ("flagged_right", "flagged & right (false alarm)"),
                   ("flagged_unjudged", "flagged, no rejected model"),
                   ("unjudgeable", "ground truth cannot tell"),
                   ("no_model", "no model, no status")]

CONFUSION_LEGEND = (
    "Each run with ground truth is in one cell: **returned & right**, **returned & wrong** "
    "(an undetected failure), **flagged & wrong** (a caught failure), **flagged & right** "
    "(a false alarm). Right: rotation error <= %.0f deg and translation direction error <= "
    "%.0f deg (pairs with a pose), or an RMS Sampson distance of the labelled true "
    "correspondences <= %.0f px (F-only pairs: AdelaideRMF, MAGSAC vpts). Flagged: an rcme "
    "status other than success; it is judged through the model the run turned down "
    "(`Report.rejectedF`, `rejectedR`, `rejectedT`); *flagged, no rejected model*: no "
    "hypothesis (or no motion) was there to judge. OpenCV's estimators have no status: only the "
    "returned cells, plus *no model* when they return none. *Ground truth cannot tell*: F-only "
    "pairs whose labelled matches fit one homography so closely that F = [e]x H passes the "
    "judge for epipoles in all of 8 directions (`metrics.epipole_blind`: 4 at infinity, 4 at "
    "%.0f px); their runs are left out of the rates." % (
        metrics.ROTATION_FAILURE_DEG, metrics.TRANSLATION_FAILURE_DEG, metrics.F_FAILURE_PX,
        metrics.BLIND_EPIPOLE_DISTANCE_PX))


def confusion_cell(row):
    """The cell of one run, or None when the pair has no ground truth."""
    if row.get("unjudgeable"):
        return "unjudgeable"
    if row["ok"]:
        if "gt_fail" not in row:
            return None
        return "returned_wrong" if row["gt_fail"] else "returned_right"
    if not row.get("flagged"):
        return "no_model"
    wrong = row.get("rejected_wrong")
    if wrong is None:
        return "flagged_unjudged"
    return "flagged_wrong" if wrong else "flagged_right"


def confusion_counts(rows):
    counts = {key: 0 for key, _ in CONFUSION_CELLS}
    for row in rows:
        cell = confusion_cell(row)
        if cell is not None:
            counts[cell] += 1
    return counts


def _count_pct(count, total):
    return "%d (%s %%)" % (count, _pct(count, total))


def confusion_rates(counts):
    """undetected % of the judged runs, caught % of the wrong ones, false alarms % of the right
    ones (a flag without a rejected model is neither: nothing was there to judge; runs on pairs
    whose ground truth cannot tell right from wrong are left out)."""
    total = sum(counts.values()) - counts["unjudgeable"]
    wrong = counts["returned_wrong"] + counts["flagged_wrong"]
    right = counts["returned_right"] + counts["flagged_right"]
    return {"runs": total, "undetected": _pct(counts["returned_wrong"], total),
            "caught": _pct(counts["flagged_wrong"], wrong),
            "false_alarm": _pct(counts["flagged_right"], right)}


def confusion_table(rows, method_names, datasets):
    """A row per dataset and method: the count (and %) of runs in each cell."""
    lines = []
    for dataset in datasets + ["all"]:
        subset = rows if dataset == "all" else _select(rows, dataset=dataset)
        for method in method_names:
            counts = confusion_counts(_select(subset, method=method))
            total = sum(counts.values())
            if total:
                rates = confusion_rates(counts)
                lines.append([dataset, method, total]
                             + [_count_pct(counts[k], total) for k, _ in CONFUSION_CELLS]
                             + [rates["caught"], rates["false_alarm"]])
    return _table(["dataset", "method", "runs"] + [label for _, label in CONFUSION_CELLS]
                  + ["caught % of wrong", "false alarms % of right"], lines)


AUC_LIMIT_DEG = 10.0


def auc(rows, limit_deg=AUC_LIMIT_DEG):
    """AUC@limit of max(rotation, translation direction error): the area under the share of runs
    within an error e for e from 0 to the limit, over the limit; that is the mean over the runs of
    max(0, 1 - e / limit). A run without a motion (a flag, no model) counts as an infinite error.
    None without runs."""
    if not rows:
        return None
    scores = [max(0.0, 1.0 - max(r["rot"], r["trans"]) / limit_deg)
              if r["ok"] and "rot" in r else 0.0 for r in rows]
    return float(np.mean(scores))


def auc_table(groups, method_names):
    """groups: [(label, rows)] of runs on pairs with a pose; a row per method, a column per
    group, AUC@10 to four digits."""
    lines = []
    for method in method_names:
        values = [auc(_select(rows, method=method)) for _, rows in groups]
        if any(v is not None for v in values):
            lines.append([method] + ["%.4f" % v if v is not None else "n/a" for v in values])
    return _table(["method"] + [label for label, _ in groups], lines)


def auc_targets(groups, ours, peer):
    """groups: [(runs label, [(group label, rows)])]; a row per group where both methods ran:
    AUC@10 of `ours` against `peer`'s and whether it is at least as high (met / not met)."""
    lines = []
    for runs, subgroups in groups:
        for label, rows in subgroups:
            a, b = auc(_select(rows, method=ours)), auc(_select(rows, method=peer))
            if a is None or b is None:
                continue
            lines.append([runs, label, "%.4f >= %.4f" % (a, b),
                          "met" if a >= b else "**not met**"])
    return _table(["runs", "dataset", "AUC@%.0f: %s >= %s" % (AUC_LIMIT_DEG, ours, peer), ""],
                  lines)


def confusion_summary(groups, method_names):
    """groups: [(label, rows)]; a row per group and method with the targets' three rates."""
    lines = []
    for label, rows in groups:
        for method in method_names:
            counts = confusion_counts(_select(rows, method=method))
            if sum(counts.values()):
                r = confusion_rates(counts)
                cells = "%d / %d / %d / %d" % tuple(counts[key] for key in (
                    "returned_right", "returned_wrong", "flagged_wrong", "flagged_right"))
                lines.append([label, method, r["runs"], counts["unjudgeable"], cells,
                              r["undetected"], r["caught"], r["false_alarm"]])
    return _table(["suite", "method", "judged runs", "unjudgeable runs",
                   "right / undetected / caught / false alarm", "undetected % of runs",
                   "caught % of wrong", "false alarms % of right"], lines)
