# Sourced by run_sanitizers.sh and run_fuzzer.sh: the one ASan + UBSan build both use.
#
# The C++ tests, the samples and the libFuzzer target share one build (clang, RCME_SANITIZE=
# address, RCME_FUZZ=ON, in build-sanitize/): the library is compiled once with the sanitizers
# and the coverage instrumentation libFuzzer needs, which the tests do not mind (the sanitizer
# runtime provides the coverage callbacks when libFuzzer is not linked). Both scripts configure
# it with the same arguments, so that whichever runs second only builds its own targets.

address_build_dir=${SANITIZE_BUILD_DIR:-build-sanitize}

# configure_address_build: configures $address_build_dir (RelWithDebInfo: -O2 like the real
# library, with line numbers in the reports).
configure_address_build() {
    cmake -S . -B "$address_build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_COMPILER=clang++ -DRCME_SANITIZE=address -DRCME_FUZZ=ON \
        -DRCME_BUILD_TESTS=ON -DRCME_BUILD_SAMPLES=ON -DRCME_BUILD_PYTHON=OFF \
        -DRCME_BUILD_PERF=OFF
}
