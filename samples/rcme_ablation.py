#!/usr/bin/python3
"""RCME's choices one at a time, and local optimisation, on the paper's corridor: the tables
"RCME on the corridor" of doc/experiments_archive.md.

Corridor, w = 0.5, sigma 1 px, N exactly, estimateRelativeMotion with K (what recoverPose runs);
every configuration sees the same scenes and the same seeds.

    PYTHONPATH=build/python /usr/bin/python3 samples/rcme_ablation.py --seeds 100
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "benchmark"))
from methods import Budget, rcme, rcme_params  # noqa: E402
from corridor import scene_params  # noqa: E402

SIGMA = 1.0

ABLATION = [
    ("Standard (reference)", rcme.METHOD_STANDARD, {}),
    ("paper literal: no sample fit, 1 DoF", rcme.METHOD_RCME, {"sampleFitIterations": 0}),
    ("paper literal, 3 DoF (the paper's settings)", rcme.METHOD_RCME,
     {"sampleFitIterations": 0, "consistencyDof": 3}),
    ("**defaults**: sample fit 5, 1 DoF, lambda 0.9, mu 1.27", rcme.METHOD_RCME, {}),
    ("defaults, 3 DoF", rcme.METHOD_RCME, {"consistencyDof": 3}),
    ("defaults, leverage-corrected samples", rcme.METHOD_RCME, {"sampleLeverage": True}),
    ("defaults, mu = 3.0", rcme.METHOD_RCME, {"entropyThreshold": 3.0}),
    ("defaults, lambda = 0.5", rcme.METHOD_RCME, {"inlierRatioFactor": 0.5}),
    ("defaults, lambda = 0.98", rcme.METHOD_RCME, {"inlierRatioFactor": 0.98}),
    ("pRCME, defaults", rcme.METHOD_PRCME, {}),
    ("pRCME, no sample fit", rcme.METHOD_PRCME, {"sampleFitIterations": 0}),
]

LOCAL_OPTIMISATION = [
    ("Standard", rcme.METHOD_STANDARD, {}),
    ("Standard + LO", rcme.METHOD_STANDARD, {"localOptimization": True}),
    ("RCME", rcme.METHOD_RCME, {}),
    ("RCME + LO", rcme.METHOD_RCME, {"localOptimization": True}),
]


def run(rows, scenes, iterations):
    print("| configuration | mean dq (std) | median dq | PQI | other failure | median ms |")
    print("|---|---|---|---|---|---|")
    for name, method, fields in rows:
        errors, pqi, other, seconds = [], 0, 0, []
        for seed, s in scenes:
            params = rcme_params(method, Budget(iterations, SIGMA, seed))
            for field, value in fields.items():
                setattr(params, field, value)
            start = time.perf_counter()
            report = rcme.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params)
            seconds.append(time.perf_counter() - start)
            if report.status == rcme.STATUS_POOR_QUALITY_INPUT:
                pqi += 1
            elif report.status != rcme.STATUS_SUCCESS:
                other += 1
            else:
                errors.append(rcme.compareMotion(report.R, report.t, s.R, s.t).dq)
        e = np.array(errors) if errors else np.array([np.nan])
        print("| %s | %.4f (%.4f) | %.4f | %.0f %% | %.0f %% | %.1f |" % (
            name, e.mean(), e.std(), np.median(e), 100.0 * pqi / len(scenes),
            100.0 * other / len(scenes), 1000 * np.median(seconds)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--inlier-ratio", type=float, default=0.5)
    ap.add_argument("--iterations", type=int, default=1000)
    args = ap.parse_args()
    scenes = [(seed, rcme.generateScene(scene_params(500, args.inlier_ratio, SIGMA, seed)))
              for seed in range(args.seeds)]
    print("corridor: seeds 0-%d, inlier ratio %.2f, exactly N = %d, with K" % (
        args.seeds - 1, args.inlier_ratio, args.iterations))
    print("\nRCME's choices (ablation)\n")
    run(ABLATION, scenes, args.iterations)
    print("\nLocal optimisation\n")
    run(LOCAL_OPTIMISATION, scenes, args.iterations)


if __name__ == "__main__":
    main()
