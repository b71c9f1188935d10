# The README's two commands. Each works on its own on a fresh Debian 12 machine: it installs the
# Debian packages that are missing (with sudo when not root), configures, builds (Release) and
# then runs the demo or every test.

BUILD_DIR ?= build
JOBS ?= 2
DEB_PACKAGES := build-essential cmake ninja-build ccache pkg-config libopencv-dev libeigen3-dev \
	libgtest-dev pybind11-dev libbenchmark-dev python3-dev python3-numpy python3-opencv \
	python3-pytest dpkg-dev zlib1g-dev libpng-dev libjpeg-dev
# INTREE=0 skips the in-tree step of make test (OpenCV built from source with the module, see
# test/opencv_intree/build_opencv_with_rcme.sh; dpkg-dev and the zlib/png/jpeg headers are for it).
INTREE ?= 1

.PHONY: demo test test-intree build configure deps

demo: build
	$(BUILD_DIR)/bin/rcme_two_view_demo --method rcme --out $(BUILD_DIR)/demo/two_view_demo.png

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)
ifneq ($(INTREE),0)
	test/opencv_intree/build_opencv_with_rcme.sh --jobs $(JOBS)
endif

test-intree: deps
	test/opencv_intree/build_opencv_with_rcme.sh --jobs $(JOBS)

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
