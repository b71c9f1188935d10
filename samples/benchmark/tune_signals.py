#!/usr/bin/python3
"""The tuning study behind the defaults' failure signals after inner sampling
(doc/experiments_archive.md, "Failure-signal tuning"): the default method, exactly
N = 1000, on synthetic scenes the benchmark does not use (corridors from seed 100: 200 seeds at
w = 0.3 and 0.5, sigma 1; 60 at sigma 0.5 and 2 and at w = 0.7; hard cases with seeds 100-129).

Each scene runs once with the uncertainty test off and the ambiguity test comparing its rivals
without flagging (margin 1e-9), so that any setting of (ambiguityMargin, maxRotationStdDeg,
maxTranslationStdDeg) is a rule on the recorded rival cost gap and standard deviations. Prints
right / undetected / caught / false alarm per setting, and the defaults' cells by suite.

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/tune_signals.py"""
import itertools

import numpy as np

import corridor
import hard_cases
import methods
import metrics
import report
from methods import rcme

CORRIDOR_SETTINGS = [(0.3, 1.0, 200), (0.5, 1.0, 200), (0.5, 2.0, 60), (0.5, 0.5, 60),
                     (0.7, 1.0, 60)]
FIRST_SEED, HARD_SEEDS = 100, 30


def tuning_pairs():
    pairs = [corridor.corridor_pair(500, w, sigma, seed) for w, sigma, count in CORRIDOR_SETTINGS
             for seed in range(FIRST_SEED, FIRST_SEED + count)]
    return pairs + hard_cases.hard_case_pairs(HARD_SEEDS, FIRST_SEED)


def record(pair):
    """The run's status, whether its motion (or the one it turned down) is wrong, and the
    measures the signals read."""
    params = methods.rcme_params(None, methods.Budget(pair.iterations or 1000, pair.sigma, 0))
    params.ambiguityMargin, params.maxRotationStdDeg, params.maxTranslationStdDeg = 1e-9, 0, 0
    r = rcme.estimateRelativeMotion(pair.points1, pair.points2, pair.K, params)
    ok = r.status == rcme.STATUS_SUCCESS
    R, t = (r.R, r.t) if ok else (r.rejectedR, r.rejectedT)
    if not np.any(pair.t_gt):
        wrong = True  # no translation: no motion is right
    elif R is None or t is None:
        wrong = None
    else:
        error = rcme.compareMotion(R, t, pair.R_gt, pair.t_gt.reshape(3, 1))
        wrong = metrics.pose_failure(error.rotationDeg, error.translationDeg)
    row = dict(suite=pair.dataset, ok=ok, wrong=wrong)
    if ok:
        row.update(gap=r.rivalCostGap, rotation_std=float(np.max(np.asarray(r.rotationStdDeg))),
                   translation_std=r.translationStdDeg)
    return row


def cells(rows, margin, rotation_bound, translation_bound):
    """right, undetected, caught, false alarm with the signals at the given setting."""
    counts = [0, 0, 0, 0]
    for row in rows:
        if row["wrong"] is None:
            continue
        flagged = not row["ok"] or (
            (margin > 0 and row["gap"] < margin) or
            (rotation_bound > 0 and row["rotation_std"] > rotation_bound) or
            (translation_bound > 0 and row["translation_std"] > translation_bound))
        if flagged:
            counts[2 if row["wrong"] else 3] += 1
        else:
            counts[1 if row["wrong"] else 0] += 1
    return counts


def main():
    rows = [record(pair) for pair in tuning_pairs()]
    lines = []
    for setting in itertools.product([0, 1, 2, 3, 4, 6, 8], [1.5, 2, 2.5, 3, 4, 5],
                                     [4, 5, 6, 7, 8, 10]):
        right, undetected, caught, false_alarm = cells(rows, *setting)
        lines.append(list(setting) + ["%d / %d / %d / %d" % (right, undetected, caught,
                                                           false_alarm),
                                      "%.1f" % (100.0 * caught / max(caught + undetected, 1)),
                                      "%.2f" % (100.0 * false_alarm / max(false_alarm + right, 1))])
    print(report._table(["margin", "max rotation std", "max translation std",
                         "right / undetected / caught / false alarm", "caught %",
                         "false alarms %"], lines))
    print()
    defaults = rcme.Params()
    suites = sorted({row["suite"] for row in rows})
    print(report._table(["suite", "right / undetected / caught / false alarm (defaults)"],
                        [[suite, "%d / %d / %d / %d" % tuple(cells(
                            [r for r in rows if r["suite"] == suite], defaults.ambiguityMargin,
                            defaults.maxRotationStdDeg, defaults.maxTranslationStdDeg))]
                         for suite in suites]))


if __name__ == "__main__":
    main()
