#!/usr/bin/env bash
# Runs the benchmark with PoseLib (https://github.com/PoseLib/PoseLib, `poselib` from PyPI) as a
# peer, in a venv this script creates: PoseLib is a benchmark-only tool, never a dependency of
# the module. The venv sees Debian's packages (--system-site-packages: NumPy, python3-opencv)
# and the built module through PYTHONPATH; the arguments go to run_benchmark.py.
#
#   samples/benchmark/with_poselib.sh [run_benchmark.py arguments]
#   samples/benchmark/with_poselib.sh --sparse-only [...]   (the sparse-pairs suite alone)
#   samples/benchmark/with_poselib.sh --speed [speed.py arguments]   (the timing side by side)
#   samples/benchmark/with_poselib.sh --vo-front-end [vo_front_end.py arguments]
#   samples/benchmark/with_poselib.sh --covariance [covariance_calibration.py arguments]
#   samples/benchmark/with_poselib.sh --f-only [f_only.py arguments]   (no K for anyone)
#   samples/benchmark/with_poselib.sh --stage-costs [stage_value.py arguments]   (what each stage
#       of the default costs and buys: doc/benchmark/stage_value.md)
# Environment: BUILD_DIR (default build), POSELIB_VENV (default $BUILD_DIR/poselib-venv),
# POSELIB_VERSION (default 2.0.5, the version measured in doc/results.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir=${BUILD_DIR:-build}
venv=${POSELIB_VENV:-$build_dir/poselib-venv}
version=${POSELIB_VERSION:-2.0.5}
if ! "$venv/bin/python" -c "import poselib" 2>/dev/null; then
    /usr/bin/python3 -m venv --system-site-packages "$venv"
    "$venv/bin/pip" install --quiet "poselib==$version"
fi
# A suite flag picks the script; the rest of the arguments are the script's.
case "${1:-}" in
    --speed) script=speed.py ;;
    --vo-front-end) script=vo_front_end.py ;;
    --covariance) script=covariance_calibration.py ;;
    --f-only) script=f_only.py ;;
    --stage-costs) script=stage_value.py ;;
    *) script=run_benchmark.py ;;
esac
[ "$script" = run_benchmark.py ] || shift
PYTHONPATH="$build_dir/python${PYTHONPATH:+:$PYTHONPATH}" \
    "$venv/bin/python" "samples/benchmark/$script" "$@"
