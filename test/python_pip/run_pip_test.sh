#!/usr/bin/env bash
# `pip install .` in a fresh virtual environment, then the Python tests on the installed package.
#
#   test/python_pip/run_pip_test.sh
#
# What a Python user does: a venv of the machine's CPython (PYTHON, default /usr/bin/python3),
# NumPy from PyPI (NUMPY, default "numpy>=2,<3"), `pip install <repo>` (scikit-build-core and
# pybind11 come from PyPI in pip's isolated build environment), then, from outside the
# repository, pytest on modules/rcme/misc/python/test (RCME_TEST_REQUIRE=standalone: a package
# that does not import fails instead of skipping), then every Python block of README.md,
# doc/python.md and the tutorials, the Dask and Ray recipe on their local schedulers (DOCS=0
# skips it); then pip's
# opencv-python-headless in the same venv and test_cv2_coexistence.py (cv2 and rcme in one
# process, arrays passed between them; COEXIST=0 skips it), after mypy on typed_use.py with
# the installed type stub (TYPECHECK=0 skips it). The venv is made anew on every run
# (BUILD_DIR/pip_test/venv, default BUILD_DIR=build); pip's download cache and the wheel's
# CMake build folder (BUILD_DIR-pip, beside BUILD_DIR so that ccache reuses the objects of the
# main build) are kept between runs.
set -euo pipefail

repo=$(cd "$(dirname "$0")/../.." && pwd)
build_dir=${BUILD_DIR:-build}
case $build_dir in /*) ;; *) build_dir=$repo/$build_dir ;; esac
python=${PYTHON:-/usr/bin/python3}
numpy_spec=${NUMPY:-numpy>=2,<3}
work=$build_dir/pip_test
venv=$work/venv

start=$(date +%s)
rm -rf "$venv"
mkdir -p "$work"
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet "$numpy_spec" pytest
# The compiler as CMake finds it by default (c++), not the interpreter's CXX, so that ccache
# matches the main build's compile lines.
CXX=${CXX:-c++} CMAKE_BUILD_PARALLEL_LEVEL=${JOBS:-2} "$venv/bin/python" -m pip install --quiet \
  --config-settings=build-dir="$build_dir-pip" "$repo"
installed=$(date +%s)

cd "$work" # not the repository: the tests must import the installed package
"$venv/bin/python" - <<'PY'
import os, numpy, rcme
folder = os.path.dirname(rcme.__file__)
assert "site-packages" in folder, folder
for name in ("__init__.pyi", "py.typed"):
    assert os.path.isfile(os.path.join(folder, name)), name
print("rcme from %s, NumPy %s" % (folder, numpy.__version__))
PY
RCME_TEST_REQUIRE=standalone PYTHONDONTWRITEBYTECODE=1 \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$repo/modules/rcme/misc/python/test"
tested=$(date +%s)
echo "run_pip_test: venv + install $((installed - start)) s, tests $((tested - installed)) s"

# The standalone module of the CMake build (BUILD_DIR/python, made with Debian's pybind11 2.10)
# under this venv's NumPy 2: pybind11 before 2.12 reads NumPy 1's dtype layout, and the module
# must not depend on it (rcme_python.cpp, dtypeKind). Skipped when that build has no Python module.
if [ -d "$build_dir/python/rcme" ]; then
  PYTHONPATH="$build_dir/python" "$venv/bin/python" -c \
    "import rcme, sys; assert rcme.__file__.startswith(sys.argv[1]), rcme.__file__" "$build_dir/python"
  # A timeout: with the NumPy 1 layout read, a result array's strides were garbage and one test hung.
  RCME_TEST_REQUIRE=standalone PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$build_dir/python" \
    timeout 600 "$venv/bin/python" -m pytest -q -p no:cacheprovider "$repo/modules/rcme/misc/python/test"
  echo "run_pip_test: the CMake build's module under NumPy $("$venv/bin/python" -c \
    'import numpy; print(numpy.__version__)') $(($(date +%s) - tested)) s"
  tested=$(date +%s)
fi

# The Python blocks of README.md, doc/python.md and the tutorials on the installed package
# (test/docs/run_python_blocks.py), with the many-machines recipe on dask's and ray's local
# schedulers: both from PyPI, into this venv only (DOCS=0 skips the step, which downloads them).
if [ "${DOCS:-1}" != 0 ]; then
  "$venv/bin/python" -m pip install --quiet dask ray
  mapfile -t tutorials < <(find "$repo/modules/rcme/tutorials" -name '*.markdown' | sort)
  PYTHONDONTWRITEBYTECODE=1 "$venv/bin/python" "$repo/test/docs/run_python_blocks.py" \
    "$repo/README.md" "$repo/doc/python.md" "${tutorials[@]}"
  echo "run_pip_test: dask + ray install, the docs' Python blocks $(($(date +%s) - tested)) s"
  tested=$(date +%s)
fi

# The type stub as an editor's checker reads it (TYPECHECK=0 skips: it downloads mypy).
if [ "${TYPECHECK:-1}" != 0 ]; then
  "$venv/bin/python" -m pip install --quiet mypy
  set +e
  out=$("$venv/bin/python" -m mypy --no-incremental "$repo/test/python_pip/typed_use.py" 2>&1)
  set -e
  echo "$out"
  if ! grep -q 'typed_use.py:16: error: "Params" has no attribute "sigmaa"' <<<"$out" ||
     ! grep -q "Found 1 error" <<<"$out"; then
    echo "run_pip_test: mypy with the stub did not give exactly the expected error" >&2
    exit 1
  fi
  echo "run_pip_test: mypy on the stub $(($(date +%s) - tested)) s"
  tested=$(date +%s)
fi

# pip's cv2 in the same process (COEXIST=0 skips: it downloads opencv-python-headless).
if [ "${COEXIST:-1}" != 0 ]; then
  "$venv/bin/python" -m pip install --quiet opencv-python-headless
  PYTHONDONTWRITEBYTECODE=1 "$venv/bin/python" -m pytest -q -p no:cacheprovider \
    "$repo/test/python_pip/test_cv2_coexistence.py"
  echo "run_pip_test: opencv-python-headless install + coexistence test $(($(date +%s) - tested)) s"
fi
