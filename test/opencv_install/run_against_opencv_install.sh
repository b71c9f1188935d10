#!/usr/bin/env bash
# The standalone build and `pip install .` against an installed OpenCV other than Debian's: the
# install tree of the in-tree build (test/opencv_intree/build_opencv_with_rcme.sh, OpenCV 5.1 by
# default), found through CMAKE_PREFIX_PATH as a user's own OpenCV would be.
#   1. the in-tree build (built if needed, its tests not run) is installed into
#      <cache>/<version>/install;
#   2. the repository is configured and built standalone against it (<cache>/<version>/standalone,
#      samples off: they need the features module, which the in-tree build leaves out), and its
#      ctest runs: C++ tests, the pybind11 module's Python tests (next to that OpenCV's own cv2,
#      the only cv2 a process may load beside those libraries), install consumer;
#   3. test/python_pip/run_pip_test.sh: `pip install .` in a fresh venv (NumPy 2) against the same
#      install and the Python tests on the installed package (without the parts that download
#      another cv2 or mypy).
# Exits non-zero on any failure.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: test/opencv_install/run_against_opencv_install.sh [--opencv VERSION] [-j N]

  --opencv VERSION   as test/opencv_intree/build_opencv_with_rcme.sh --opencv (default 5.1)
  -j, --jobs N       parallel jobs (default: $JOBS or 2)
EOF
}

REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OPENCV_CHOICE="${OPENCV:-5.1}"
JOBS="${JOBS:-2}"
while [ $# -gt 0 ]; do
  case "$1" in
    --opencv) OPENCV_CHOICE="${2:?--opencv needs a version}"; shift 2 ;;
    --opencv=*) OPENCV_CHOICE="${1#*=}"; shift ;;
    -j|--jobs) JOBS="${2:?--jobs needs a number}"; shift 2 ;;
    --jobs=*) JOBS="${1#*=}"; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "error: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
START=$SECONDS
step() { printf '\n==> [%4ds] %s\n' "$((SECONDS - START))" "$*"; }
die() { echo "error: $*" >&2; exit 1; }

step "In-tree build of OpenCV $OPENCV_CHOICE (built if needed; its tests are not run here)"
intree_log="$(mktemp)"
"$REPO_DIR/test/opencv_intree/build_opencv_with_rcme.sh" --opencv "$OPENCV_CHOICE" \
  --jobs "$JOBS" --no-tests 2>&1 | tee "$intree_log"
build_dir="$(sed -n 's/^Build folder: *//p' "$intree_log" | tail -n1)"
rm -f "$intree_log"
[ -f "$build_dir/CMakeCache.txt" ] || die "no in-tree build folder found in the script's output"
version_dir="$(dirname "$build_dir")"
prefix="$version_dir/install"

step "Installing it into $prefix"
rm -rf "$prefix"
cmake --install "$build_dir" --prefix "$prefix" >"$version_dir/install.log" \
  || { tail -n 30 "$version_dir/install.log"; die "cmake --install failed"; }
opencv_dir="$(dirname "$(find "$prefix" -name OpenCVConfig.cmake | head -n1)")"
[ -d "$opencv_dir" ] || die "no OpenCVConfig.cmake under $prefix"
cv2_dir="$(dirname "$(find "$prefix" -path '*-packages/cv2/__init__.py' | head -n1)")"
[ -d "$cv2_dir" ] || die "no cv2 package under $prefix"
# The libraries of the install, for the test programs and the Python modules (OpenCV installs
# them without a run path).
export CMAKE_PREFIX_PATH="$prefix"
export LD_LIBRARY_PATH="$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# cv2 of the same install: Debian's python3-opencv (4.6) in one process with these libraries
# would mix two OpenCVs.
export PYTHONPATH="$(dirname "$cv2_dir")"
echo "OpenCV_DIR: $opencv_dir; cv2: $cv2_dir"

standalone="$version_dir/standalone"
step "Standalone build against it ($standalone)"
cmake -S "$REPO_DIR" -B "$standalone" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DRCME_BUILD_SAMPLES=OFF >"$version_dir/standalone-configure.log" \
  || { tail -n 30 "$version_dir/standalone-configure.log"; die "configure failed"; }
grep -E "^-- rcme: OpenCV" "$version_dir/standalone-configure.log"
grep -q "^-- rcme: OpenCV .*($opencv_dir)" "$version_dir/standalone-configure.log" \
  || die "the standalone build did not find the OpenCV of $prefix"
cmake --build "$standalone" -j"$JOBS"

step "ctest of the standalone build"
/usr/bin/python3 -c "import cv2, sys; print('cv2', cv2.__version__, cv2.__file__); \
sys.exit(0 if cv2.__file__.startswith('$prefix') else 'cv2 is not the one of $prefix')"
# Not the Python samples: they detect features with cv2.SIFT, and the in-tree build has no
# features module.
(cd "$standalone" && ctest --output-on-failure -j"$JOBS" \
  -E '^(rcme_python_sample.*|rcme_python_verify_image_folder)$')

step "pip install . against it, and the Python tests on the installed package"
# NumPy 2 from PyPI in that venv, and no cv2 (this cv2 is built against Debian's NumPy 1.24).
env -u PYTHONPATH JOBS="$JOBS" BUILD_DIR="$version_dir/pip" TYPECHECK=0 COEXIST=0 \
  "$REPO_DIR/test/python_pip/run_pip_test.sh"

step "Done: standalone build, ctest and pip install . against OpenCV $OPENCV_CHOICE ($prefix)"
