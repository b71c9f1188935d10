// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_VECTOR_CLONES_HPP
#define OPENCV_RCME_GEOMETRY_VECTOR_CLONES_HPP

// For the loops over every point of every hypothesis (residual_bands.cpp,
// residual_uncertainty.cpp).
//
// RCME_VECTOR_CLONES: GCC's function multi-versioning, an AVX2 clone beside the baseline one,
// chosen once by the loader; the loops vectorize four points wide on AVX2. AVX2 without FMA, so
// both clones round alike and a result does not depend on the machine.
//
// RCME_WIDE_VECTOR_CLONES adds an AVX-512 clone, for the band's count alone (residual_bands.cpp,
// compiled with -ffp-contract=off: AVX-512F has fused multiply-adds, which would round otherwise).
// Eight points wide it counts large inputs faster; on the fits' short blocks and the other loops
// AVX-512 made whole calls slower (doc/performance.md, "Large inputs"). Clang and other targets
// get the baseline only, and so do sanitizer builds: the loader runs the clones' resolver before
// ThreadSanitizer's runtime is up, and the instrumented resolver crashed the TSan test binary at
// start.
//
// RCME_ALWAYS_INLINE: for the per-point arithmetic a clone calls, so that it is compiled into each
// clone (and vectorized there) instead of called.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&       \
    !defined(__SANITIZE_THREAD__) && !defined(__SANITIZE_ADDRESS__)
#define RCME_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#define RCME_WIDE_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define RCME_VECTOR_CLONES
#define RCME_WIDE_VECTOR_CLONES
#endif
// RCME_SPECULATIVE_MATH: a loop whose per-point choices (a select between two computed values)
// may compute both sides, divisions included, instead of branching: GCC otherwise keeps a
// division that could trap inside a branch, and a loop with a branch does not vectorize. No value
// changes (traps are not enabled).
#if defined(__GNUC__) && !defined(__clang__)
#define RCME_SPECULATIVE_MATH __attribute__((optimize("no-trapping-math")))
#else
#define RCME_SPECULATIVE_MATH
#endif
#if defined(__GNUC__)
#define RCME_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define RCME_ALWAYS_INLINE inline
#endif

#endif // OPENCV_RCME_GEOMETRY_VECTOR_CLONES_HPP
