#pragma once
/// REGOLITH_SIMD_CLONES before a hot kernel compiles it three times, for x86-64-v4
/// (AVX-512), x86-64-v3 (AVX2 + FMA, 4 doubles per vector) and the baseline, and picks one at
/// load time from the CPU (GCC function multi-versioning). The v4 clone was ~20% faster than
/// v3 for the tree's list kernel on the project's EPYC VM (bench/gravity). The build needs no
/// -march, and the binary still runs on any x86-64. The AVX clones may contract a * b + c into an
/// FMA (GCC's default for C++), which changes rounding; a kernel whose bits matter is compiled with
/// -ffp-contract=off (the direct sum, gravity/CMakeLists.txt).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define REGOLITH_SIMD_CLONES                                                                       \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define REGOLITH_SIMD_CLONES
#endif
