#!/usr/bin/python3
"""Where the error of Standard and RCME on the corridor comes from: the same scenes and exactly-N
runs as corridor_comparison.py, but with oracle knowledge removed step by step.

- all points: the usual run;
- true band: only the points within the threshold of the true F (the true inliers that fall in
  the band, plus the outliers that happen to): the best any selection could be given;
- true inliers only: the labelled inliers, no outliers at all;
and, for the usual run, how the final model's support (points within the threshold of its F)
compares with the support of the true F.

    PYTHONPATH=build/python /usr/bin/python3 samples/corridor_error_sources.py --seeds 100
"""
import argparse

import numpy as np

try:
    import rcme
except ImportError:  # built inside OpenCV
    import cv2
    rcme = cv2.rcme

THRESHOLD_IN_SIGMAS = 1.959963984540054


def sampson_distance(F, p1, p2):
    x1 = np.c_[p1, np.ones(len(p1))]
    x2 = np.c_[p2, np.ones(len(p2))]
    Fx1, Ftx2 = x1 @ F.T, x2 @ F
    numerator = np.sum(x2 * Fx1, axis=1) ** 2
    denominator = Fx1[:, 0] ** 2 + Fx1[:, 1] ** 2 + Ftx2[:, 0] ** 2 + Ftx2[:, 1] ** 2
    return np.sqrt(numerator / denominator)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--inlier-ratio", type=float, default=0.5)
    ap.add_argument("--iterations", type=int, default=1000)
    ap.add_argument("--inlier-ratio-factor", type=float, default=None,
                    help="RCME's lambda (default: the library's)")
    args = ap.parse_args()

    methods = {"Standard": rcme.METHOD_STANDARD, "RCME": rcme.METHOD_RCME}
    inputs = ("all points", "true band", "true inliers only")
    dq = {(m, i): [] for m in methods for i in inputs}
    failures = {key: 0 for key in dq}
    support_deficit = {m: [] for m in methods}
    for seed in range(args.seeds):
        sp = rcme.SceneParams()
        sp.inlierRatio, sp.seed = args.inlier_ratio, seed
        s = rcme.generateScene(sp)
        threshold = THRESHOLD_IN_SIGMAS * sp.sigma
        true_support = sampson_distance(s.F, s.points1, s.points2) <= threshold
        selections = {"all points": np.ones(len(s.points1), bool), "true band": true_support,
                      "true inliers only": s.inlierMask.ravel() == 1}
        for name, method in methods.items():
            params = rcme.Params()
            params.method, params.sigma = method, sp.sigma
            params.maxIterations, params.exactIterations = args.iterations, True
            params.randomGeneratorState = seed
            if args.inlier_ratio_factor is not None:
                params.inlierRatioFactor = args.inlier_ratio_factor
            for input_name, keep in selections.items():
                rep = rcme.estimateRelativeMotion(s.points1[keep], s.points2[keep],
                                                  s.cameraMatrix, params)
                if rep.status != rcme.STATUS_SUCCESS:
                    failures[(name, input_name)] += 1
                    continue
                dq[(name, input_name)].append(rcme.compareMotion(rep.R, rep.t, s.R, s.t).dq)
                if input_name == "all points":
                    final = sampson_distance(rep.F, s.points1, s.points2) <= threshold
                    support_deficit[name].append(int(true_support.sum()) - int(final.sum()))

    print("corridor: %d seeds, n = %d, inlier ratio %.2f, sigma %.2f px, exactly N = %d" %
          (args.seeds, sp.numPoints, args.inlier_ratio, sp.sigma, args.iterations))
    print("| method | input | mean dq | median dq | 90th pct dq | failures |")
    print("|---|---|---|---|---|---|")
    for (name, input_name), values in dq.items():
        v = np.array(values) if values else np.array([np.nan])
        print("| %s | %s | %.4f | %.4f | %.4f | %d |" % (
            name, input_name, v.mean(), np.median(v), np.percentile(v, 90),
            failures[(name, input_name)]))
    for name, deficit in support_deficit.items():
        d = np.array(deficit)
        print("%s, all points: the true F's support exceeds the final model's by %.1f points "
              "on average (median %.0f; the final model has more in %d %% of the scenes)" %
              (name, d.mean(), np.median(d), round(100 * np.mean(d < 0))))


if __name__ == "__main__":
    main()
