# The README's two commands. Each works on its own on a fresh Debian 12 machine: it installs the
# Debian packages that are missing (with sudo when not root), configures, builds (Release) and
# then runs the demo or every test.

BUILD_DIR ?= build
JOBS ?= 2
DEB_PACKAGES := build-essential cmake ninja-build ccache pkg-config libopencv-dev libeigen3-dev \
	libgtest-dev pybind11-dev libbenchmark-dev python3-dev python3-numpy python3-opencv \
	python3-pytest dpkg-dev zlib1g-dev libpng-dev libjpeg-dev clang libclang-rt-14-dev python3-venv \
	doxygen texlive-binaries
# doxygen and texlive-binaries (its bibtex, for the headers' citations) are for make docs.
# INTREE=0 skips the in-tree step of make test (OpenCV built from source with the module, see
# test/opencv_intree/build_opencv_with_rcme.sh; python3-venv and the zlib/png/jpeg headers are for
# it, dpkg-dev for OPENCV=debian).
INTREE ?= 1
# The OpenCV of the in-tree step (make test and make test-intree): 5.1 or 4.14 (PyPI's
# opencv-contrib-python sdist, with opencv_contrib), or debian (the source package of the
# installed OpenCV, 4.6 on Debian 12).
OPENCV ?= 5.1
# Length of the fuzzing run of make test / make fuzz, seconds (doc/hardening.md; clang and
# libclang-rt-14-dev are for the fuzzer: libFuzzer and clang's ASan runtime).
FUZZ_SECONDS ?= 60

# ccache (used by every build when installed) keys on the compiler's command line: with the
# checkout as base directory and without the working directory in the hash (the sanitizer builds
# have -g), a fresh clone in another folder reuses the objects of the previous one.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR = 1

# make docs: the API reference (doc/Doxyfile) in $(BUILD_DIR)/doc/html; any doxygen warning fails it.
.PHONY: demo docs test test-intree test-opencv-install test-pip sanitize sanitize-thread fuzz build configure deps

demo: build
	$(BUILD_DIR)/bin/rcme_two_view_demo --method rcme --out $(BUILD_DIR)/demo/two_view_demo.png

# Every part in order (packages, Release build, ctest, make docs, pip, ASan + UBSan, TSan, fuzzing,
# in-tree OpenCV 5.1), ending with a table of the parts and their wall times (test/run_test_parts.sh).
test:
	BUILD_DIR=$(BUILD_DIR) JOBS=$(JOBS) FUZZ_SECONDS=$(FUZZ_SECONDS) INTREE=$(INTREE) \
	  OPENCV=$(OPENCV) MAKE="$(MAKE)" test/run_test_parts.sh

# The API reference of the public headers and the tutorials (doc/Doxyfile), warnings as errors.
# Without texmf.cnf (texlive-base is not needed) bibtex finds the bibliography and doxygen's
# style, both copied into doxygen's output folder, only through BIBINPUTS and BSTINPUTS.
docs: deps
	rm -rf $(BUILD_DIR)/doc
	( cat doc/Doxyfile; echo "OUTPUT_DIRECTORY = $(BUILD_DIR)/doc" ) | BIBINPUTS=. BSTINPUTS=. doxygen -
	@echo "API reference: $(BUILD_DIR)/doc/html/index.html"

# ASan + UBSan build (build-sanitize/, clang, shared with the fuzzer) and every C++ test under it.
sanitize: deps
	JOBS=$(JOBS) test/hardening/run_sanitizers.sh

# TSan build (build-tsan/) and the concurrency tests under it.
sanitize-thread: deps
	JOBS=$(JOBS) test/hardening/run_sanitizers.sh --tsan

# libFuzzer on the public API (build-sanitize/) for FUZZ_SECONDS.
fuzz: deps
	JOBS=$(JOBS) test/hardening/run_fuzzer.sh $(FUZZ_SECONDS)

# `pip install .` in a fresh venv (NumPy 2 from PyPI) and the Python tests on the installed package.
test-pip: deps
	JOBS=$(JOBS) BUILD_DIR=$(BUILD_DIR) test/python_pip/run_pip_test.sh

test-intree: deps
	test/opencv_intree/build_opencv_with_rcme.sh --opencv $(OPENCV) --jobs $(JOBS)

# The standalone build (ctest) and `pip install .` against the install tree of the in-tree
# build of OPENCV (5.1 by default) instead of Debian's OpenCV.
test-opencv-install: deps
	test/opencv_install/run_against_opencv_install.sh --opencv $(OPENCV) --jobs $(JOBS)

build: configure
	cmake --build $(BUILD_DIR) -j$(JOBS)

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release

deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${db:Status-Status}' $$p 2>/dev/null | grep -qx installed || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing Debian packages:$$missing"; \
	  if [ "$$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi; \
	  $$sudo apt-get update && \
	  $$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $$missing; \
	fi
