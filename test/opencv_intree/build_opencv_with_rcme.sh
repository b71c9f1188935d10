#!/usr/bin/env bash
# Builds OpenCV with the rcme module (this repository's modules/ as OPENCV_EXTRA_MODULES_PATH)
# and its Python bindings, then runs the module's tests against that build:
#   1. opencv_test_rcme, the C++ tests compiled with OpenCV's ts (the component tests of
#      test_components.cpp are compiled out in-tree by design);
#   2. the Python tests with pytest against the in-tree cv2 (which must be the one imported and
#      must have cv2.rcme: RCME_TEST_REQUIRE=cv2 turns a skip into an error);
#   3. the same tests under OpenCV's own runner (modules/python/test/test.py), where the cv2
#      test class derives from NewOpenCVTests.
# Exits non-zero on any failure.
#
# Where the OpenCV source comes from (--opencv):
#   5.1 (the default, make test's) or 4.14: the PyPI sdist of opencv-contrib-python at the pinned
#     version below, which carries opencv/ and opencv_contrib/; it is fetched once with
#     `pip download` (from a throwaway venv with scikit-build and numpy, which pip's metadata step
#     needs) and the build gets opencv_contrib's modules beside rcme, as a contrib user has them;
#   debian: the Debian source package of the installed OpenCV (`apt-get source
#     opencv=<installed version>`, 4.6 on Debian 12; the script enables deb-src in apt's sources
#     when needed, with sudo when not root).
# --opencv-src DIR uses your own source tree instead (any 4.x or 5.x; an opencv_contrib/modules
# beside it is used too, or give --contrib DIR).
# The sources and the builds are cached outside the repository, in
#   ${RCME_OPENCV_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/rcme-opencv}/<version>/{src,build}
# so a second run on the same machine (from any clone) only rebuilds what changed. CMake is
# configured on every run: OpenCV globs the module's files only at configure time.
#
# Only the modules rcme needs are built (core imgproc flann and the module with
# findFundamentalMat & co.: calib3d with features2d in 4.x, geometry in 5.1, 3d in 5.0; plus
# imgcodecs videoio highgui ts for the C++ tests and python3), with system libraries and without
# any download (IPP, ADE, ITT, protobuf, optional codecs and GUI are off; the configure step fails
# if OpenCV tried to download anything). ccache is used when installed.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: test/opencv_intree/build_opencv_with_rcme.sh [options]

  --opencv VERSION   5.1 (default) or 4.14: the source of PyPI's opencv-contrib-python sdist
                     (with opencv_contrib); debian: the Debian source package of the
                     installed OpenCV (4.6 on Debian 12)
  --opencv-src DIR   build this OpenCV 4.x or 5.x source tree instead
  --contrib DIR      opencv_contrib's modules folder to add beside rcme (default: the sdist's,
                     or DIR/../opencv_contrib/modules for --opencv-src DIR when it exists)
  --build-dir DIR    build folder (default: <cache>/<version>/build)
  -j, --jobs N       parallel jobs (default: $JOBS or 2)
  --python PATH      Python 3 interpreter to build cv2 for and run the tests with
                     (default: /usr/bin/python3, which has Debian's numpy and pytest)
  --no-tests         build only
  -h, --help         this help

Environment: OPENCV (as --opencv), RCME_OPENCV_CACHE (cache folder), XDG_CACHE_HOME,
CCACHE_DIR, JOBS.
EOF
}

REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
MODULES_DIR="$REPO_DIR/modules"
PY_TEST_DIR="$MODULES_DIR/rcme/misc/python/test"
# HOME may be unset in a bare CI environment (set -u would stop on it): fall back to passwd.
HOME_DIR="${HOME:-$(getent passwd "$(id -u)" | cut -d: -f6)}"
CACHE_ROOT="${RCME_OPENCV_CACHE:-${XDG_CACHE_HOME:-$HOME_DIR/.cache}/rcme-opencv}"

OPENCV_SRC=""
OPENCV_CHOICE="${OPENCV:-5.1}"
CONTRIB_DIR=""
BUILD_DIR=""
JOBS="${JOBS:-2}"
PYTHON="/usr/bin/python3"
RUN_TESTS=1

while [ $# -gt 0 ]; do
  case "$1" in
    --opencv) OPENCV_CHOICE="${2:?--opencv needs a version}"; shift 2 ;;
    --opencv=*) OPENCV_CHOICE="${1#*=}"; shift ;;
    --contrib) CONTRIB_DIR="${2:?--contrib needs a folder}"; shift 2 ;;
    --contrib=*) CONTRIB_DIR="${1#*=}"; shift ;;
    --opencv-src) OPENCV_SRC="${2:?--opencv-src needs a folder}"; shift 2 ;;
    --opencv-src=*) OPENCV_SRC="${1#*=}"; shift ;;
    --build-dir) BUILD_DIR="${2:?--build-dir needs a folder}"; shift 2 ;;
    --build-dir=*) BUILD_DIR="${1#*=}"; shift ;;
    -j|--jobs) JOBS="${2:?--jobs needs a number}"; shift 2 ;;
    -j*) JOBS="${1#-j}"; shift ;;
    --jobs=*) JOBS="${1#*=}"; shift ;;
    --python) PYTHON="${2:?--python needs a path}"; shift 2 ;;
    --python=*) PYTHON="${1#*=}"; shift ;;
    --no-tests) RUN_TESTS=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "error: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

SCRIPT_START=$SECONDS
step() { printf '\n==> [%4ds] %s\n' "$((SECONDS - SCRIPT_START))" "$*"; }
die() { echo "error: $*" >&2; exit 1; }

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
as_root() {
  if [ -n "$SUDO" ] && ! command -v sudo >/dev/null; then
    die "'$*' needs root and sudo is not installed"
  fi
  $SUDO "$@"
}

# --- Debian packages the in-tree build needs (the Makefile's deps target installs them too)
NEEDED_PACKAGES="build-essential cmake ninja-build pkg-config libeigen3-dev zlib1g-dev \
libpng-dev libjpeg-dev python3-dev python3-numpy python3-pytest"
# The pinned PyPI sdists of --opencv: opencv-contrib-python's version for each OpenCV release.
SDIST_VERSION=""
if [ -z "$OPENCV_SRC" ]; then
  case "$OPENCV_CHOICE" in
    5.1 | 5.1.0 | 5.1.0.95) SDIST_VERSION=5.1.0.95 ;;
    4.14 | 4.14.0 | 4.14.0.94) SDIST_VERSION=4.14.0.94 ;;
    debian) NEEDED_PACKAGES="$NEEDED_PACKAGES dpkg-dev" ;;
    *) echo "error: --opencv: 5.1, 4.14 or debian, not '$OPENCV_CHOICE' (or --opencv-src DIR)" >&2
       exit 2 ;;
  esac
  [ -n "$SDIST_VERSION" ] && NEEDED_PACKAGES="$NEEDED_PACKAGES python3-venv"
fi
if command -v dpkg-query >/dev/null; then
  missing=""
  for p in $NEEDED_PACKAGES; do
    dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -qx installed \
      || missing="$missing $p"
  done
  if [ -n "$missing" ]; then
    step "Installing missing Debian packages:$missing"
    as_root apt-get update
    # shellcheck disable=SC2086  # a list of package names
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $missing
  fi
fi
[ -x "$PYTHON" ] || die "Python interpreter $PYTHON not found (--python)"

# --- The OpenCV source

# deb-src entries for the sources apt already uses: deb822 files (Debian 12's
# /etc/apt/sources.list.d/debian.sources) get deb-src added to their Types: lines; a one-line
# sources.list gets a deb-src twin of each deb line in sources.list.d/rcme-deb-src.list.
enable_deb_src() {
  local deb822=/etc/apt/sources.list.d/debian.sources
  mkdir -p "$CACHE_ROOT"
  if [ -f "$deb822" ] && grep -Eq '^Types:.*\bdeb\b' "$deb822"; then
    cp "$deb822" "$CACHE_ROOT/debian.sources.orig-$(date +%Y%m%d%H%M%S)"
    echo "Adding deb-src to the Types: lines of $deb822 (original saved in $CACHE_ROOT)"
    as_root sed -i -E '/^Types:/{/deb-src/!s/$/ deb-src/}' "$deb822"
  elif [ -f /etc/apt/sources.list ] && grep -Eq '^deb[[:space:]]' /etc/apt/sources.list; then
    echo "Adding deb-src twins of /etc/apt/sources.list's deb lines in" \
      "/etc/apt/sources.list.d/rcme-deb-src.list"
    grep -E '^deb[[:space:]]' /etc/apt/sources.list | sed -E 's/^deb([[:space:]])/deb-src\1/' \
      | as_root tee /etc/apt/sources.list.d/rcme-deb-src.list >/dev/null
  else
    die "found no apt source to add deb-src to; pass --opencv-src DIR"
  fi
}

opencv_version_of() {  # "4.6.0" from a source tree's version.hpp
  local h="$1/modules/core/include/opencv2/core/version.hpp"
  [ -f "$h" ] || return 1
  local v
  v="$(awk '/#define CV_VERSION_(MAJOR|MINOR|REVISION)[[:space:]]/ {printf "%s.", $3}' "$h")"
  echo "${v%.}"
}

if [ -n "$SDIST_VERSION" ]; then
  VERSION="$SDIST_VERSION"
  VERSION_DIR="$CACHE_ROOT/pypi-opencv-contrib-python-$SDIST_VERSION"
  OPENCV_SRC="$VERSION_DIR/src/opencv"
  [ -n "$CONTRIB_DIR" ] || CONTRIB_DIR="$VERSION_DIR/src/opencv_contrib/modules"
elif [ -n "$OPENCV_SRC" ]; then
  OPENCV_SRC="$(cd "$OPENCV_SRC" && pwd)" || die "no folder $OPENCV_SRC"
  if [ -z "$CONTRIB_DIR" ] && [ -d "$OPENCV_SRC/../opencv_contrib/modules" ]; then
    CONTRIB_DIR="$(cd "$OPENCV_SRC/../opencv_contrib/modules" && pwd)"
  fi
  VERSION="$(opencv_version_of "$OPENCV_SRC")" \
    || die "$OPENCV_SRC is not an OpenCV source tree (no modules/core/include/opencv2/core/version.hpp)"
  VERSION_DIR="$CACHE_ROOT/$VERSION-src-$(printf '%s' "$OPENCV_SRC" | sha1sum | cut -c1-8)"
else
  command -v dpkg-query >/dev/null || die "not a Debian system: pass --opencv-src DIR"
  SRC_PKG=""; SRC_VERSION=""
  for bin in libopencv-dev libopencv-core-dev; do
    if dpkg-query -W -f='${db:Status-Status}' "$bin" 2>/dev/null | grep -qx installed; then
      SRC_PKG="$(dpkg-query -W -f='${source:Package}' "$bin")"
      SRC_VERSION="$(dpkg-query -W -f='${source:Version}' "$bin")"
      break
    fi
  done
  [ -n "$SRC_VERSION" ] || die "the Debian OpenCV is not installed (make deps), or pass --opencv-src DIR"
  VERSION="$SRC_VERSION"
  VERSION_DIR="$CACHE_ROOT/$SRC_VERSION"
  OPENCV_SRC="$VERSION_DIR/src"
fi
BUILD_DIR="${BUILD_DIR:-$VERSION_DIR/build}"
mkdir -p "$BUILD_DIR"
BUILD_DIR="$(cd "$BUILD_DIR" && pwd)"

# One run at a time per build folder (another clone, or the same one twice).
exec 9>"$BUILD_DIR/.rcme-build.lock"
if ! flock -n 9; then
  echo "Waiting for another run that uses $BUILD_DIR ..."
  flock 9
fi

if [ ! -f "$OPENCV_SRC/.rcme-source-complete" ] && [ -n "${SRC_PKG:-}" ]; then
  step "Fetching the Debian source of $SRC_PKG $SRC_VERSION into $OPENCV_SRC"
  if ! apt-get source --print-uris "$SRC_PKG=$SRC_VERSION" >/dev/null 2>&1; then
    # shellcheck disable=SC2016  # apt's own $(...) syntax
    if ! apt-get indextargets --format '$(IDENTIFIER)' 2>/dev/null | grep -qx Sources; then
      enable_deb_src
    fi
    as_root apt-get update
  fi
  apt-get source --print-uris "$SRC_PKG=$SRC_VERSION" >/dev/null 2>&1 \
    || die "apt cannot find the source package $SRC_PKG=$SRC_VERSION (is it still in the archive?); pass --opencv-src DIR"
  fetch="$VERSION_DIR/fetch.tmp"
  rm -rf "$fetch" "$OPENCV_SRC"
  mkdir -p "$fetch"
  # apt-get source unpacks with dpkg-source -x, which applies Debian's patches.
  (cd "$fetch" && apt-get source -q "$SRC_PKG=$SRC_VERSION")
  unpacked="$(find "$fetch" -mindepth 1 -maxdepth 1 -type d -name "$SRC_PKG-*" | head -n1)"
  if [ -z "$unpacked" ] || [ ! -f "$unpacked/CMakeLists.txt" ]; then
    die "apt-get source unpacked nothing in $fetch"
  fi
  mv "$unpacked" "$OPENCV_SRC"
  rm -rf "$fetch"
  touch "$OPENCV_SRC/.rcme-source-complete"
fi
# The sdist: fetched by pip (the one network access, to PyPI), unpacked without its Python
# packaging, kept with a marker once complete.
if [ -n "$SDIST_VERSION" ] && [ ! -f "$VERSION_DIR/src/.rcme-source-complete" ]; then
  step "Fetching opencv-contrib-python==$SDIST_VERSION (sdist) from PyPI into $VERSION_DIR/src"
  venv="$CACHE_ROOT/pip-download-venv"
  if [ ! -x "$venv/bin/pip" ]; then
    rm -rf "$venv"
    /usr/bin/python3 -m venv "$venv"
    # pip runs the sdist's metadata step (setup.py), which imports skbuild and numpy.
    "$venv/bin/pip" install -q --disable-pip-version-check scikit-build numpy
  fi
  fetch="$VERSION_DIR/fetch.tmp"
  rm -rf "$fetch" "$VERSION_DIR/src"
  mkdir -p "$fetch"
  "$venv/bin/pip" download -q --disable-pip-version-check --no-binary :all: --no-deps \
    --no-build-isolation -d "$fetch" "opencv-contrib-python==$SDIST_VERSION"
  archive="$(find "$fetch" -maxdepth 1 -name "opencv_contrib_python-$SDIST_VERSION.tar.gz" | head -n1)"
  [ -n "$archive" ] || die "pip downloaded no opencv_contrib_python-$SDIST_VERSION.tar.gz into $fetch"
  top="opencv_contrib_python-$SDIST_VERSION"
  tar -xzf "$archive" -C "$fetch" "$top/opencv" "$top/opencv_contrib"
  mkdir -p "$VERSION_DIR/src"
  mv "$fetch/$top/opencv" "$fetch/$top/opencv_contrib" "$VERSION_DIR/src/"
  rm -rf "$fetch"
  touch "$VERSION_DIR/src/.rcme-source-complete"
fi
[ -f "$OPENCV_SRC/CMakeLists.txt" ] || die "no OpenCV source in $OPENCV_SRC"
if [ -n "$CONTRIB_DIR" ]; then
  CONTRIB_DIR="$(cd "$CONTRIB_DIR" && pwd)" || die "no folder $CONTRIB_DIR (--contrib)"
fi
SRC_VERSION_NUMBER="$(opencv_version_of "$OPENCV_SRC")"

# --- The module, copied to one place per build folder
# OpenCV's build refers to the module's files by path. Built from the clone's own modules/, every
# fresh clone (CI's) is a new path and ninja recompiles all of the module, and ccache misses too.
# The build therefore reads a copy beside it, updated file by file: a file whose content did not
# change keeps its time stamp, so only what a clone changed is rebuilt.
sync_tree() { # sync_tree SRC DST
  local src=$1 dst=$2 f
  mkdir -p "$dst"
  while IFS= read -r -d '' f; do
    if ! cmp -s "$src/$f" "$dst/$f"; then
      mkdir -p "$(dirname "$dst/$f")"
      cp "$src/$f" "$dst/$f"
    fi
  done < <(cd "$src" && find . -type f ! -name '*.pyc' -print0)
  while IFS= read -r -d '' f; do
    [ -e "$src/$f" ] || rm -f "$dst/$f"
  done < <(cd "$dst" && find . -type f -print0)
}
CLONE_MODULES_DIR="$MODULES_DIR"
MODULES_DIR="$BUILD_DIR/rcme-modules"
PY_TEST_DIR="$MODULES_DIR/rcme/misc/python/test"
sync_tree "$CLONE_MODULES_DIR" "$MODULES_DIR"

# The module that declares findFundamentalMat & co. and what it needs (the module's CMakeLists.txt
# picks the same one): geometry (5.1 on), 3d (5.0), calib3d with features2d (4.x).
if [ -d "$OPENCV_SRC/modules/geometry" ]; then
  GEOMETRY_MODULES=geometry
elif [ -d "$OPENCV_SRC/modules/3d" ]; then
  GEOMETRY_MODULES=3d
else
  GEOMETRY_MODULES=features2d,calib3d
fi
EXTRA_MODULES="$MODULES_DIR"
[ -z "$CONTRIB_DIR" ] || EXTRA_MODULES="$MODULES_DIR;$CONTRIB_DIR"

echo "OpenCV source: $OPENCV_SRC (OpenCV $SRC_VERSION_NUMBER)"
echo "contrib:       ${CONTRIB_DIR:-(none)}"
echo "Build folder:  $BUILD_DIR"
echo "rcme modules:  $MODULES_DIR (a copy of $CLONE_MODULES_DIR)"

# --- Configure (every run: picks up added or removed files of the module)

CCACHE_FLAG=OFF
if command -v ccache >/dev/null; then CCACHE_FLAG=ON; fi

# shellcheck disable=SC2054  # BUILD_LIST is a comma-separated list
CMAKE_ARGS=(
  -G Ninja
  -DCMAKE_BUILD_TYPE=Release
  -DOPENCV_EXTRA_MODULES_PATH="$EXTRA_MODULES"
  # python_tests writes opencv_python_tests.cfg (the test folders OpenCV's runner collects).
  -DBUILD_LIST=core,imgproc,flann,$GEOMETRY_MODULES,imgcodecs,videoio,highgui,ts,python3,python_tests,rcme
  -DBUILD_opencv_python3=ON -DBUILD_opencv_python2=OFF
  -DPYTHON3_EXECUTABLE="$PYTHON" -DPYTHON_DEFAULT_EXECUTABLE="$PYTHON"
  -DBUILD_TESTS=ON -DBUILD_PERF_TESTS=OFF -DBUILD_EXAMPLES=OFF -DBUILD_DOCS=OFF
  -DBUILD_opencv_apps=OFF -DBUILD_JAVA=OFF -DOPENCV_GENERATE_PKGCONFIG=OFF
  -DENABLE_CCACHE="$CCACHE_FLAG"
  # No dispatched SSE4/AVX/AVX2/AVX512 variants: a third fewer files to compile, and the
  # tests do not need them. The baseline (SSE3 on x86-64) stays.
  -DCPU_DISPATCH=
  # rcme needs Eigen (Debian's libeigen3-dev).
  -DWITH_EIGEN=ON
  # Nothing that would be downloaded (Debian's source tree has no 3rdparty/ either).
  -DWITH_IPP=OFF -DWITH_ADE=OFF -DWITH_ITT=OFF -DWITH_PROTOBUF=OFF -DWITH_CAROTENE=OFF
  -DWITH_QUIRC=OFF -DWITH_LAPACK=OFF -DWITH_TBB=OFF -DWITH_OPENCL=OFF -DWITH_CUDA=OFF
  -DWITH_VA=OFF -DWITH_VA_INTEL=OFF
  # Options of newer OpenCVs (older ones ignore them, with a warning): nothing the tests do not
  # need.
  -DWITH_FLATBUFFERS=OFF -DWITH_HARFBUZZ=OFF -DBUILD_HARFBUZZ=OFF -DWITH_KLEIDICV=OFF
  -DWITH_FASTCV=OFF -DWITH_OPENVINO=OFF -DWITH_OBSENSOR=OFF -DWITH_AVIF=OFF -DWITH_SPNG=OFF
  # imgcodecs with the system zlib, libpng and libjpeg only; no video or GUI backends.
  -DBUILD_ZLIB=OFF -DBUILD_PNG=OFF -DBUILD_JPEG=OFF -DBUILD_TIFF=OFF -DBUILD_WEBP=OFF
  -DBUILD_OPENJPEG=OFF -DBUILD_OPENEXR=OFF -DBUILD_JASPER=OFF
  -DWITH_PNG=ON -DWITH_JPEG=ON -DWITH_TIFF=OFF -DWITH_WEBP=OFF -DWITH_OPENJPEG=OFF
  -DWITH_JASPER=OFF -DWITH_OPENEXR=OFF -DWITH_GDAL=OFF -DWITH_GDCM=OFF
  -DWITH_FFMPEG=OFF -DWITH_GSTREAMER=OFF -DWITH_1394=OFF -DWITH_GPHOTO2=OFF -DWITH_V4L=OFF
  -DWITH_GTK=OFF -DWITH_QT=OFF -DWITH_OPENGL=OFF -DWITH_VTK=OFF
)

step "Configuring OpenCV (log: $BUILD_DIR/rcme-configure.log)"
if ! cmake -S "$OPENCV_SRC" -B "$BUILD_DIR" "${CMAKE_ARGS[@]}" >"$BUILD_DIR/rcme-configure.log" 2>&1; then
  tail -n 60 "$BUILD_DIR/rcme-configure.log"
  die "CMake configure failed (full log: $BUILD_DIR/rcme-configure.log)"
fi
grep -E "Extra modules:|Location \(extra\)|To be built:|Disabled:|Unavailable:|Python 3:|Interpreter:|numpy:|Eigen:|ccache" \
  "$BUILD_DIR/rcme-configure.log" || true
grep -Eq "To be built:.*\brcme\b" "$BUILD_DIR/rcme-configure.log" \
  || die "OpenCV's configure did not enable the rcme module (see $BUILD_DIR/rcme-configure.log)"
# OpenCV logs every download attempt after its "#use_cache" header line.
if [ -f "$BUILD_DIR/CMakeDownloadLog.txt" ] && grep -vq '^#use_cache' "$BUILD_DIR/CMakeDownloadLog.txt"; then
  cat "$BUILD_DIR/CMakeDownloadLog.txt"
  die "OpenCV's configure tried to download something (above); the build must not download"
fi

# --- Build

step "Building opencv_rcme, opencv_test_rcme and cv2 (ninja -j$JOBS)"
ninja -C "$BUILD_DIR" -j"$JOBS" opencv_rcme opencv_test_rcme opencv_python3 \
  2>&1 | tee "$BUILD_DIR/rcme-build.log"

if [ "$RUN_TESTS" -eq 0 ]; then
  step "Built (tests not run)"
  exit 0
fi

# --- Tests
failures=0
summary=()

step "C++ tests: $BUILD_DIR/bin/opencv_test_rcme"
if (cd "$BUILD_DIR" && ./bin/opencv_test_rcme 2>&1 | tee "$BUILD_DIR/rcme-test-cpp.log"); then
  summary+=("C++ (opencv_test_rcme): $(grep -E '^\[  PASSED  \]' "$BUILD_DIR/rcme-test-cpp.log" | tail -n1 || true)")
else
  failures=$((failures + 1))
  summary+=("C++ (opencv_test_rcme): FAILED")
fi

# Run everything Python from the build folder with only the in-tree loader on the path.
export PYTHONPATH="$BUILD_DIR/python_loader"
export PYTHONDONTWRITEBYTECODE=1
export RCME_TEST_REQUIRE=cv2
unset PYTHONHOME || true

step "Checking that $PYTHON imports the in-tree cv2 with rcme"
"$PYTHON" - "$BUILD_DIR" "$MODULES_DIR" <<'EOF'
import os, sys
build = os.path.realpath(sys.argv[1])
modules = {sys.argv[2], os.path.realpath(sys.argv[2])}  # as given to CMake, and resolved
import cv2
native = getattr(getattr(cv2, "_native", None), "__file__", "?")
print("cv2.__file__:", cv2.__file__)
print("native module:", native, "| OpenCV", cv2.__version__)
libs = sorted({line.split()[-1] for line in open("/proc/self/maps") if "libopencv_core" in line})
print("libopencv_core:", ", ".join(libs))
under = lambda p: os.path.realpath(p).startswith(build + os.sep)
errors = []
if not under(cv2.__file__) or not under(native):
    errors.append("cv2 is not the one of %s" % build)
if not libs or not all(under(p) for p in libs):
    errors.append("cv2 runs with a libopencv_core from outside %s" % build)
if not hasattr(cv2, "rcme"):
    errors.append("cv2 has no rcme")
extra = [line.split(":", 1)[1].strip() for line in cv2.getBuildInformation().splitlines()
         if "Location (extra):" in line]
if not set(extra) & modules:
    errors.append("cv2 was not built with the extra modules of %s" % sys.argv[2])
if errors:
    sys.exit("error: " + "; ".join(errors))
print("cv2.rcme:", len([n for n in dir(cv2.rcme) if not n.startswith("_")]), "names")
EOF

step "Python tests (pytest) against the in-tree cv2.rcme"
if (cd "$BUILD_DIR" && "$PYTHON" -m pytest -q -rs -p no:cacheprovider "$PY_TEST_DIR" \
      2>&1 | tee "$BUILD_DIR/rcme-test-pytest.log"); then
  summary+=("Python, pytest: $(grep -E '^[0-9]+ passed' "$BUILD_DIR/rcme-test-pytest.log" | tail -n1 | sed -E 's/ in [0-9.]+s.*//' || true)")
else
  failures=$((failures + 1))
  summary+=("Python, pytest: FAILED")
fi

step "Python tests under OpenCV's runner (modules/python/test/test.py, OPENCV_PYTEST_FILTER=test_rcme*)"
if (cd "$BUILD_DIR" && OPENCV_PYTEST_FILTER='test_rcme*' "$PYTHON" \
      "$OPENCV_SRC/modules/python/test/test.py" --repo "$OPENCV_SRC" 2>&1 \
      | tee "$BUILD_DIR/rcme-test-opencv-runner.log") \
   && grep -q "$PY_TEST_DIR" "$BUILD_DIR/rcme-test-opencv-runner.log"; then
  summary+=("Python, OpenCV's runner: $(grep -E '^Ran [0-9]+ tests' "$BUILD_DIR/rcme-test-opencv-runner.log" | tail -n1 | sed -E 's/ in [0-9.]+s//' || true), $(tail -n1 "$BUILD_DIR/rcme-test-opencv-runner.log")")
else
  failures=$((failures + 1))
  summary+=("Python, OpenCV's runner: FAILED (or the rcme test folder was not collected)")
fi

step "Summary (OpenCV $SRC_VERSION_NUMBER in $BUILD_DIR)"
printf '  %s\n' "${summary[@]}"
if [ "$failures" -ne 0 ]; then
  die "$failures in-tree test step(s) failed"
fi
