#!/usr/bin/env python3
# This file is part of the rcme module. It is subject to the license terms in the LICENSE file
# found in the top-level directory of this distribution.
"""Pairs per second of rcme.estimateRelativeMotionBatch against Python loops of single calls.

On the same synthetic pairs (generic scenes with their camera matrix, fixed seeds) it times:
a Python loop of rcme.estimateRelativeMotion; the batch call on 1, 2, ... threads; and, for
comparison, single calls spread over a ThreadPoolExecutor of the same thread counts (possible
because every call releases the GIL). Each figure is the best of --repeats runs; every run's
Reports are checked to equal the loop's (timeSeconds aside).

    PYTHONPATH=build/python /usr/bin/python3 samples/batch_throughput.py [--pairs 200]
        [--points 500] [--method standard] [--threads 1,2] [--repeats 3]

Numbers for doc/performance.md; not run by the tests.
"""

import argparse
import concurrent.futures
import os
import platform
import sys
import time

import numpy as np

import rcme

from two_view_demo import method_names, parse_method


def same_report(a, b):
    sa, sb = a.__getstate__(), b.__getstate__()
    for name in sa:
        if name == "timeSeconds":
            continue
        x, y = sa[name], sb[name]
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            if x is None or y is None or not np.array_equal(x, y):
                return False
        elif isinstance(x, float) and np.isnan(x):
            if not np.isnan(y):
                return False
        elif x != y:
            return False
    return True


def best_of(repeats, run, reference, count):
    """(best pairs/s, least CPU ms per pair, whether every run gave the reference Reports)."""
    best, cpu, same = 0.0, float("inf"), True
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        reports = run()
        best = max(best, count / (time.perf_counter() - start))
        cpu = min(cpu, 1000 * (time.process_time() - start_cpu) / count)
        same = same and len(reports) == len(reference) and all(
            same_report(r, q) for r, q in zip(reports, reference))
    return best, cpu, same


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", type=int, default=200)
    ap.add_argument("--points", type=int, default=500)
    ap.add_argument("--inlier-ratio", type=float, default=0.5)
    ap.add_argument("--method", default="standard", help=method_names())
    ap.add_argument("--threads", default="1,2", help="comma-separated thread counts")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    threads = [int(t) for t in args.threads.split(",")]

    scenes = [rcme.generateScene(rcme.SceneParams(kind=rcme.SCENE_GENERIC, seed=1000 + i,
                                                  numPoints=args.points,
                                                  inlierRatio=args.inlier_ratio))
              for i in range(args.pairs)]
    pairs = [(s.points1, s.points2) for s in scenes]
    K = scenes[0].cameraMatrix  # the generic scenes share their camera
    params = rcme.Params(method=parse_method(rcme, args.method), randomGeneratorState=1)

    def loop():
        return [rcme.estimateRelativeMotion(p1, p2, K, params) for p1, p2 in pairs]

    reference = loop()
    n = len(pairs)
    print("%d pairs, %d points, inlier ratio %.2f, %s; %s, %d CPUs (os.cpu_count), load %s"
          % (n, args.points, args.inlier_ratio, args.method, platform.processor() or
             platform.machine(), os.cpu_count(), "%.1f %.1f %.1f" % os.getloadavg()))
    rate, cpu, same = best_of(args.repeats, loop, reference, n)
    print("%-34s %8.1f pairs/s %6.2f CPU ms/pair" % ("Python loop of single calls", rate, cpu))
    for t in threads:
        rate, cpu, same = best_of(
            args.repeats, lambda: rcme.estimateRelativeMotionBatch(pairs, K, params, t),
            reference, n)
        print("%-34s %8.1f pairs/s %6.2f CPU ms/pair  %s" % (
            "batch, %d thread(s)" % t, rate, cpu, "same Reports" if same else "DIFFERENT"))
    for t in threads:
        with concurrent.futures.ThreadPoolExecutor(t) as pool:
            rate, cpu, same = best_of(args.repeats, lambda: list(pool.map(
                lambda pq: rcme.estimateRelativeMotion(pq[0], pq[1], K, params), pairs)),
                reference, n)
        print("%-34s %8.1f pairs/s %6.2f CPU ms/pair  %s" % (
            "single calls on %d Python thread(s)" % t, rate, cpu,
            "same Reports" if same else "DIFFERENT"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
