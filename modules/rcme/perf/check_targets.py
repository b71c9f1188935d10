#!/usr/bin/python3
"""The speed targets of the perf suite, computed from ONE run of opencv_perf_rcme.

Either runs the benchmark binary itself with JSON output, pinned to one core (taskset -c 0),
except the parallel benchmarks, which need every core:

    /usr/bin/python3 modules/rcme/perf/check_targets.py --binary build/bin/opencv_perf_rcme \
        --save build/perf.json

or reads the JSON of a run made by hand (--benchmark_format=json or --benchmark_out=FILE):

    /usr/bin/python3 modules/rcme/perf/check_targets.py --json build/perf.json

Ratios use each benchmark's CPU time (one thread; robust to other processes sharing the core),
except the parallel speed-up, which is wall-clock by nature. Prints one line per target with
"met" or "NOT MET" and exits with status 1 when any target is not met. Targets (doc/performance.md):

- RCME at exactly N = 1000, n = 500 costs at most 1.5x Standard's time on the same data (camera
  motion, with K);
- time grows linearly in n: n = 10000 costs at most 25x n = 500 (exactly N = 1000);
- time grows linearly in N: N = 1000 costs at most 5x N = 200 (10 % allowance for timing noise);
- rcme's Standard (F, exactly N) is no slower than OpenCV's findFundamentalMat FM_RANSAC at the same
  exact iteration count.
"""

import argparse
import json
import re
import shutil
import subprocess
import sys

NAME = re.compile(r"^call/(?P<method>[^/]+)/(?P<model>[KF])/n:(?P<n>\d+)/N:(?P<N>\d+)/"
                  r"(?P<mode>exact|adaptive)$")
PARALLEL = re.compile(r"^parallel/(?P<method>[^/]+)/K/n:(?P<n>\d+)/N:(?P<N>\d+)/exact/"
                      r"threads:(?P<threads>\d+)(/real_time)?$")
LINEAR_NOISE = 1.10


def run_benchmark(binary, save):
    """Everything but the parallel benchmarks pinned to core 0; those on every core."""
    report = None
    for pinned, selection in ((True, "^(call|solver|score)"), (False, "^parallel/")):
        command = [binary, "--benchmark_format=json", f"--benchmark_filter={selection}"]
        if pinned and shutil.which("taskset"):
            command = ["taskset", "-c", "0"] + command
        print("running:", " ".join(command), file=sys.stderr)
        output = subprocess.run(command, check=True, stdout=subprocess.PIPE, text=True).stdout
        part = json.loads(output)
        if report is None:
            report = part
        else:
            report["benchmarks"] += part["benchmarks"]
    if save:
        with open(save, "w") as f:
            json.dump(report, f, indent=1)
    return report


def to_ms(entry, key):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[entry.get("time_unit", "ns")]
    return entry[key] * scale


def collect(report):
    """Call times (CPU ms) and their report counters, parallel wall times, and the component
    benchmarks (CPU ns per solver call, per scored point)."""
    calls, counters, parallel, components = {}, {}, {}, {}
    for entry in report["benchmarks"]:
        if entry.get("run_type", "iteration") != "iteration" or entry.get("error_occurred"):
            continue
        if entry["name"].startswith(("solver/", "score-per-point/")):
            per_item = entry["name"].startswith("score-per-point/")
            components[entry["name"]] = (1e9 / entry["items_per_second"] if per_item
                                         else to_ms(entry, "cpu_time") * 1e6)
            continue
        m = NAME.match(entry["name"])
        if m:
            key = (m["method"], m["model"], int(m["n"]), int(m["N"]), m["mode"])
            calls[key] = to_ms(entry, "cpu_time")
            counters[key] = entry
            continue
        m = PARALLEL.match(entry["name"])
        if m:
            parallel[(m["method"], int(m["threads"]))] = to_ms(entry, "real_time")
    return calls, counters, parallel, components


def print_stage_budget(components, counters):
    """Where a hypothesis' time goes at n = 500 (K), from the component benchmarks of the same
    run: the solver, RCME's instantiation with and without its fit to the sample, and scoring
    at the number of points each method evaluates per hypothesis (the call's counter)."""
    names = ("solver/8-point", "solver/RCME-instantiation(8-point,fit5,covariance)",
             "solver/RCME-instantiation(8-point,fit0,covariance)", "score-per-point/count",
             "score-per-point/RCME")
    standard_key, rcme_key = [(m, "K", 500, 1000, "exact") for m in ("standard", "rcme")]
    if any(name not in components for name in names) or rcme_key not in counters:
        return
    solver, fitted, unfitted, count, entropy = (components[name] for name in names)
    rcme_points = counters[rcme_key].get("pointsPerHypothesis", 500)
    standard_points = counters.get(standard_key, {}).get("pointsPerHypothesis", 500)
    print("\nPer-hypothesis stages at n = 500 (CPU us, component benchmarks of this run):")
    print(f"         Standard: 8-point {solver / 1e3:.2f} + inlier count "
          f"{standard_points:.0f} pts x {count:.1f} ns = {(solver + standard_points * count) / 1e3:.2f}")
    print(f"         RCME: 8-point, E, motion and covariance {unfitted / 1e3:.2f} + fit to the "
          f"sample {(fitted - unfitted) / 1e3:.2f} + entropy scoring {rcme_points:.0f} pts "
          f"x {entropy:.1f} ns = {(fitted + rcme_points * entropy) / 1e3:.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--binary", help="opencv_perf_rcme to run (pinned to core 0)")
    source.add_argument("--json", help="JSON output of a run")
    parser.add_argument("--save", help="with --binary: keep the JSON here")
    parser.add_argument("--smoke", action="store_true",
                        help="exit 0 whatever the ratios, 1 only if a benchmark is missing (the "
                             "ctest smoke run: one repetition each, its timings mean nothing)")
    args = parser.parse_args()
    if args.binary:
        report = run_benchmark(args.binary, args.save)
    else:
        with open(args.json) as f:
            report = json.load(f)
    calls, counters, parallel, components = collect(report)
    context = report.get("context", {})
    print(f"host {context.get('host_name', '?')}, {context.get('num_cpus', '?')} CPUs at "
          f"{context.get('mhz_per_cpu', '?')} MHz, load average "
          f"{context.get('load_avg', '?')}, {context.get('date', '?')}")

    results = []

    def check(label, value, limit, unit="x"):
        met = value <= limit
        results.append(met)
        print(f"{'met    ' if met else 'NOT MET'}  {label}: {value:.2f}{unit} (target <= {limit}{unit})")

    def info(label, value, unit="x"):
        print(f"         {label}: {value:.2f}{unit}")

    def get(method, model, n, N, mode="exact"):
        key = (method, model, n, N, mode)
        if key not in calls:
            sys.exit(f"missing benchmark call/{method}/{model}/n:{n}/N:{N}/{mode}")
        return calls[key]

    print("\nRCME against Standard, same data, exactly N = 1000, n = 500 (CPU ms):")
    standard_k, rcme_k = get("standard", "K", 500, 1000), get("rcme", "K", 500, 1000)
    print(f"         Standard {standard_k:.2f} ms, RCME {rcme_k:.2f} ms (camera motion, K)")
    check("RCME / Standard (K)", rcme_k / standard_k, 1.5)
    info("RCME / Standard without K (F)", get("rcme", "F", 500, 1000) / get("standard", "F", 500, 1000))
    for model in ("K", "F"):
        key = ("rcme-sampleFit0", model, 500, 1000, "exact")
        if key in calls:
            outcome = "succeeds" if counters[key].get("success") else "FAILS on this scene"
            info(f"RCME with sampleFitIterations 0 ({outcome}) / Standard ({model})",
                 calls[key] / get("standard", model, 500, 1000))
    print_stage_budget(components, counters)

    print("\nLinear in n (exactly N = 1000): time(n = 10000) / time(n = 500):")
    for method, model in (("standard", "K"), ("rcme", "K"), ("standard", "F")):
        check(f"{method} ({model})", get(method, model, 10000, 1000) / get(method, model, 500, 1000),
              25)

    print("\nLinear in N (exactly N): time(N = 1000) / time(N = 200):")
    for method, model in (("standard", "K"), ("rcme", "K"), ("standard", "F")):
        for n in (100, 500, 2000, 10000):
            check(f"{method} ({model}), n = {n}",
                  get(method, model, n, 1000) / get(method, model, n, 200), 5 * LINEAR_NOISE)

    print("\nrcme's Standard (F) / OpenCV findFundamentalMat FM_RANSAC, same exact N:")
    for n in (100, 500, 2000, 10000):
        for N in (200, 1000):
            check(f"n = {n}, N = {N}",
                  get("standard", "F", n, N) / get("OpenCV_FM_RANSAC", "F", n, N), 1.0)

    if parallel:
        print("\nParams.isParallel, wall-clock speed-up of 2 threads over 1 (n = 2000, N = 1000, K):")
        for method in sorted({m for m, _ in parallel}):
            if (method, 1) in parallel and (method, 2) in parallel:
                info(f"{method} ({parallel[(method, 1)]:.1f} ms -> {parallel[(method, 2)]:.1f} ms)",
                     parallel[(method, 1)] / parallel[(method, 2)])

    print(f"\n{sum(results)} of {len(results)} targets met")
    return 0 if all(results) or args.smoke else 1


if __name__ == "__main__":
    sys.exit(main())
