#!/usr/bin/python3
"""The tuning study behind Params.cleanSampleSuccessRate (doc/experiments_archive.md, "Adaptive
termination"): the default method with adaptive termination on synthetic scenes whose seeds the
benchmark does not use (corridor seeds 100-299, hard cases 100-109; the benchmark reports on
0-49 and 0-9), for several q. Prints per q and suite: right / undetected / caught / false alarm
and the median time per call.

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/tune_termination.py [q ...]"""
import sys

import numpy as np

import corridor
import evaluate
import hard_cases
import methods
import report

TUNING_CORRIDOR_SEEDS = range(100, 300)
TUNING_HARD_FIRST, TUNING_HARD_SEEDS = 100, 10
CELLS = [key for key, _ in report.CONFUSION_CELLS]


def suites():
    return [("corridor w=0.5", [corridor.corridor_pair(500, 0.5, 1.0, s)
                                for s in TUNING_CORRIDOR_SEEDS]),
            ("corridor w=0.7", [corridor.corridor_pair(500, 0.7, 1.0, s)
                                for s in TUNING_CORRIDOR_SEEDS[:50]]),
            ("hard cases", hard_cases.hard_case_pairs(TUNING_HARD_SEEDS, TUNING_HARD_FIRST))]


def main(rates):
    published = methods.rcme_params
    lines = []
    for rate in rates:
        def with_rate(method, budget, rate=rate):
            params = published(method, budget)
            params.cleanSampleSuccessRate = rate
            return params
        methods.rcme_params = with_rate
        for label, pairs in suites():
            rows = [evaluate.evaluate(methods.DEFAULT_METHOD, pair,
                                      methods.Budget(pair.iterations or 1000, pair.sigma, 0,
                                                     adaptive=True))
                    for pair in pairs]
            counts = report.confusion_counts(rows)
            ms = np.median([1000 * r["seconds"] for r in rows])
            lines.append([rate, label, len(rows)] + [counts[k] for k in CELLS]
                         + ["%.1f" % ms])
            print(lines[-1], flush=True)
    methods.rcme_params = published
    print(report._table(["q", "suite", "runs"] + CELLS + ["median ms"], lines))


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or [1.0, 0.5, 0.3, 0.2])
