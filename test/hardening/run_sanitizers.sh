#!/usr/bin/env bash
# Sanitizer jobs (doc/hardening.md). Any sanitizer report fails the test that triggered it, and so
# the script.
#
#   test/hardening/run_sanitizers.sh            ASan + UBSan (clang, RCME_SANITIZE=address): the
#                                               library, every C++ test and the samples in
#                                               build-sanitize/ (shared with run_fuzzer.sh, see
#                                               address_build.sh), every ctest entry there
#   test/hardening/run_sanitizers.sh --tsan     TSan (gcc, RCME_SANITIZE=thread) in build-tsan/:
#                                               the concurrency tests only, so only their file
#                                               is compiled besides the library
# Sanitized tests run their small sizes (testRuns in modules/rcme/test/test_precomp.hpp).
# Environment: JOBS (default 2), SANITIZE_BUILD_DIR (default build-sanitize or build-tsan).
set -euo pipefail
cd "$(dirname "$0")/../.."

mode=address
if [ "${1:-}" = "--tsan" ]; then
    mode=thread
elif [ -n "${1:-}" ]; then
    echo "usage: $0 [--tsan]" >&2
    exit 2
fi
jobs=${JOBS:-2}
here=$(pwd)
start=$(date +%s)

if [ "$mode" = address ]; then
    # shellcheck source=address_build.sh
    . test/hardening/address_build.sh
    build_dir=$address_build_dir
    # Every report is fatal (the code is also built with -fno-sanitize-recover=all). Leak checking
    # stays on: no suppression is needed for OpenCV's or TBB's libraries (measured, see
    # doc/hardening.md), so none is installed.
    export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
    export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
    test_filter=()
    configure_address_build
    # Every target, the fuzz targets of run_fuzzer.sh among them (the library is shared).
    nice cmake --build "$build_dir" -j"$jobs"
else
    build_dir=${SANITIZE_BUILD_DIR:-build-tsan}
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1${TSAN_OPTIONS:+:$TSAN_OPTIONS}"
    test_filter=(-R "Concurrency")
    cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRCME_SANITIZE=thread \
        -DRCME_BUILD_TESTS=ON -DRCME_TESTS_CONCURRENCY_ONLY=ON -DRCME_BUILD_PYTHON=OFF \
        -DRCME_BUILD_PERF=OFF -DRCME_BUILD_SAMPLES=OFF
    nice cmake --build "$build_dir" -j"$jobs"
fi
built=$(date +%s)

(cd "$build_dir" && ctest --output-on-failure -j"$jobs" "${test_filter[@]}")
done_at=$(date +%s)
echo "run_sanitizers.sh ($mode, $here/$build_dir): build $((built - start)) s, tests $((done_at - built)) s"
