#!/usr/bin/env bash
# Fuzz job (doc/hardening.md): builds the libFuzzer target rcme_fuzz_public_api with Debian's
# clang (libFuzzer + ASan + UBSan, RCME_FUZZ=ON) in build-sanitize/, the build of the ASan tests
# (address_build.sh), writes the seed corpus with
# rcme_fuzz_seeds and fuzzes for a bounded time. A crash, a sanitizer report, an exception other
# than cv::Exception, a broken output contract or an input slower than -timeout fails the script;
# libFuzzer then leaves the input in build-sanitize/fuzz/ (crash-*, timeout-*) to replay with
# `build-sanitize/bin/rcme_fuzz_public_api <file>`.
#
#   test/hardening/run_fuzzer.sh [SECONDS]     default 60 (CI: make fuzz FUZZ_SECONDS=60)
# Environment: JOBS (build, default 2), SANITIZE_BUILD_DIR (default build-sanitize).
set -euo pipefail
cd "$(dirname "$0")/../.."

seconds=${1:-60}
case "$seconds" in
'' | *[!0-9]*)
    echo "usage: $0 [SECONDS]" >&2
    exit 2
    ;;
esac
# shellcheck source=address_build.sh
. test/hardening/address_build.sh
build_dir=$address_build_dir
jobs=${JOBS:-2}
start=$(date +%s)

configure_address_build
nice cmake --build "$build_dir" -j"$jobs" --target rcme_fuzz_public_api rcme_fuzz_seeds
built=$(date +%s)

fuzz_dir="$build_dir/fuzz"
seeds="$fuzz_dir/seeds"
corpus="$fuzz_dir/corpus" # grows across local runs; CI starts from the seeds only
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus"
"$build_dir/bin/rcme_fuzz_seeds" "$seeds"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
log="$fuzz_dir/last_run.log"
# -timeout: one input slower than 10 s is reported as a hang (an execution takes milliseconds).
# -max_len: above the largest input the format reads (kMaxPoints per view, fuzz_input.hpp).
# -entropic=0: libFuzzer's entropic power schedule recomputes feature frequencies on every input,
# a quarter of an execution at this corpus size; the classic schedule explores as far here.
status=0
"$build_dir/bin/rcme_fuzz_public_api" -max_total_time="$seconds" -timeout=10 -entropic=0 \
    -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 -artifact_prefix="$fuzz_dir/" \
    "$corpus" "$seeds" >"$log" 2>&1 || status=$?
grep -E "^(INFO: Seed|#[0-9]+ +(INITED|DONE))|stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb" "$log" || true
if [ "$status" -ne 0 ]; then
    tail -n 60 "$log"
    echo "run_fuzzer.sh: FAILED (exit $status), full log in $log" >&2
    exit "$status"
fi
echo "run_fuzzer.sh: build $((built - start)) s, fuzzing ${seconds} s, no finding (log: $log)"
