#!/usr/bin/env bash
# make test: runs every part of the test suite in order, times each one and ends with a table
# of the parts and their wall times (also when a part fails, so that a budget regression or a
# failure is visible in every CI log). The budget is stated in doc/testing.md: at most 45
# minutes on a cold 2-core machine, at most 15 minutes warm.
#
# Environment (set by the Makefile): BUILD_DIR, JOBS, FUZZ_SECONDS, INTREE (0 skips the in-tree
# OpenCV part), OPENCV (the in-tree part's OpenCV, default 5.1), MAKE.
set -uo pipefail
cd "$(dirname "$0")/.."

build_dir=${BUILD_DIR:-build}
jobs=${JOBS:-2}
fuzz_seconds=${FUZZ_SECONDS:-60}
intree=${INTREE:-1}
opencv=${OPENCV:-5.1}
make_cmd=${MAKE:-make}

names=()
times=()
results=()
total_start=$SECONDS

print_table() {
    printf '\n%-44s %10s  %s\n' "make test part" "wall time" "result"
    local i
    for i in "${!names[@]}"; do
        printf '%-44s %7d s  %s\n' "${names[$i]}" "${times[$i]}" "${results[$i]}"
    done
    printf '%-44s %7d s  (%d min %d s)\n' "total" "$((SECONDS - total_start))" \
        "$(((SECONDS - total_start) / 60))" "$(((SECONDS - total_start) % 60))"
}

# part [--required] NAME COMMAND...: runs the command and records its wall time. A failed part
# does not stop the suite (every later part still runs and is timed, so one CI log shows every
# failure and the whole budget), unless it is --required (the packages and the Release build,
# which the later parts need); make test then exits with the first failure's status.
first_failure=0
part() {
    local required=0
    if [ "$1" = --required ]; then
        required=1
        shift
    fi
    local name=$1
    shift
    printf '\n==== make test: %s\n' "$name"
    local start=$SECONDS status=0
    "$@" || status=$?
    names+=("$name")
    times+=("$((SECONDS - start))")
    if [ "$status" -eq 0 ]; then
        results+=("ok")
        return
    fi
    results+=("FAILED (exit $status)")
    echo "make test: '$name' failed" >&2
    [ "$first_failure" -ne 0 ] || first_failure=$status
    if [ "$required" -eq 1 ]; then
        print_table
        exit "$status"
    fi
}

part --required "Debian packages (make deps)" "$make_cmd" --no-print-directory deps
part --required "configure + Release build ($build_dir)" "$make_cmd" --no-print-directory build \
    BUILD_DIR="$build_dir" JOBS="$jobs"
part "ctest, Release" bash -c "cd '$build_dir' && ctest --output-on-failure -j'$jobs'"
part "API reference (make docs)" "$make_cmd" --no-print-directory docs BUILD_DIR="$build_dir"
part "pip install . in a venv, Python tests" env JOBS="$jobs" BUILD_DIR="$build_dir" \
    test/python_pip/run_pip_test.sh
part "ASan + UBSan build and C++ tests" env JOBS="$jobs" test/hardening/run_sanitizers.sh
part "TSan build and concurrency tests" env JOBS="$jobs" test/hardening/run_sanitizers.sh --tsan
part "fuzzing ($fuzz_seconds s)" env JOBS="$jobs" test/hardening/run_fuzzer.sh "$fuzz_seconds"
if [ "$intree" != 0 ]; then
    part "in-tree OpenCV $opencv build and its tests" \
        test/opencv_intree/build_opencv_with_rcme.sh --opencv "$opencv" --jobs "$jobs"
fi
print_table
if [ "$first_failure" -ne 0 ]; then
    failed=()
    for i in "${!names[@]}"; do
        [ "${results[$i]}" = ok ] || failed+=("'${names[$i]}'")
    done
    echo "make test: failed: ${failed[*]}" >&2
    exit "$first_failure"
fi
