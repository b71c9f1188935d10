#!/usr/bin/python3
"""Time of the default on 10^6 correspondences (doc/performance.md, "Large inputs"): the corridor
at inlier ratio 0.5, scene seed 1, with K, one thread, exactly N = 1000 and adaptive (at most N,
the default confidence). Each given build's Python module runs in its own process, the builds in
turn, --repeats rounds; a build's time is the median of its calls (the estimation alone, not the
scene's generation), and the ratio of two builds is the median of the ratios of their calls of one
round.

    /usr/bin/python3 samples/benchmark/large_input.py build [/path/to/other/build/python ...]

Each argument is a folder holding the `rcme` module (BUILD/python or a build folder)."""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

# One call in a fresh process: the scene is generated there and only the estimation is timed.
CHILD = r"""
import json, sys, time
import cv2
import rcme
cv2.setNumThreads(1)
sp = rcme.SceneParams()
sp.numPoints, sp.inlierRatio, sp.seed = %d, 0.5, 1
scene = rcme.generateScene(sp)
out = {}
for mode in ("exact", "adaptive"):
    params = rcme.Params()
    params.maxIterations = %d
    params.exactIterations = mode == "exact"
    start = time.perf_counter()
    report = rcme.estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params)
    seconds = time.perf_counter() - start
    error = rcme.compareMotion(report.R, report.t, scene.R, scene.t)
    out[mode] = {"seconds": seconds, "status": int(report.status), "iterations": report.iterations,
                 "rotation_deg": error.rotationDeg, "translation_deg": error.translationDeg}
print(json.dumps(out))
"""


def module_path(folder):
    python = os.path.join(folder, "python")
    return python if os.path.isdir(os.path.join(python, "rcme")) else folder


def call(folder, points, iterations):
    env = dict(os.environ, PYTHONPATH=module_path(folder), PYTHONDONTWRITEBYTECODE="1")
    out = subprocess.run([sys.executable, "-c", CHILD % (points, iterations)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("builds", nargs="+")
    ap.add_argument("--points", type=int, default=1000000)
    ap.add_argument("--iterations", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    runs = {b: [] for b in args.builds}
    for _ in range(args.repeats):
        for build in args.builds:
            runs[build].append(call(build, args.points, args.iterations))
    first = args.builds[0]
    for build in args.builds:
        for mode in ("exact", "adaptive"):
            seconds = [r[mode]["seconds"] for r in runs[build]]
            last = runs[build][-1][mode]
            line = "%s %s: median %.2f s (%s), status %d, %d iterations, errors %.3f / %.3f deg" % (
                build, mode, np.median(seconds), ", ".join("%.2f" % s for s in seconds),
                last["status"], last["iterations"], last["rotation_deg"], last["translation_deg"])
            if build != first:
                ratios = [r[mode]["seconds"] / f[mode]["seconds"]
                          for r, f in zip(runs[build], runs[first])]
                line += "; / %s: %.2f" % (first, np.median(ratios))
            print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
