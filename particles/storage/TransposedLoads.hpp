#pragma once
/// Loads of the grains' 3-vectors (centres, velocities, spins: arrays of Vec3) by index into
/// structure-of-arrays lanes, four copies at a time: four loads and seven shuffles in 256-bit
/// registers, where a gather per component costs ~2.5x more and a copy element by element ties
/// the lane loop's loads to stores they must merge (store forwarding).
///
/// For the files compiled with the lane code generation (cmake/RegolithTargets.cmake): the
/// functions have internal linkage, so that each file gets the instructions of its own flags.
#include <cstddef>
#include <cstdint>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace regolith::particles::lane_loads {

/// The Vec3s at base + 3 idx[0..3] into x[0..3], y[0..3], z[0..3], without reading past z of
/// the last one (a copy's Vec3 may end its array).
[[gnu::always_inline]] static inline void transposed4(double const* base, std::uint32_t const* idx,
                                                      double* x, double* y, double* z) {
#if defined(__AVX__)
    __m256i const xyz = _mm256_setr_epi64x(-1, -1, -1, 0);
    __m256d r[4]; // (x_k y_k z_k 0)
    for (int k = 0; k < 4; ++k)
        r[k] = _mm256_maskload_pd(base + 3 * std::size_t{idx[k]}, xyz);
    __m256d const xz01 = _mm256_unpacklo_pd(r[0], r[1]); // x0 x1 z0 z1
    __m256d const y01 = _mm256_unpackhi_pd(r[0], r[1]);  // y0 y1 0 0
    __m256d const xz23 = _mm256_unpacklo_pd(r[2], r[3]); // x2 x3 z2 z3
    __m256d const y23 = _mm256_unpackhi_pd(r[2], r[3]);  // y2 y3 0 0
    _mm256_storeu_pd(x, _mm256_permute2f128_pd(xz01, xz23, 0x20));
    _mm256_storeu_pd(y, _mm256_permute2f128_pd(y01, y23, 0x20));
    _mm256_storeu_pd(z, _mm256_permute2f128_pd(xz01, xz23, 0x31));
#else
    for (int k = 0; k < 4; ++k) {
        double const* p = base + 3 * std::size_t{idx[k]};
        x[k] = p[0];
        y[k] = p[1];
        z[k] = p[2];
    }
#endif
}

} // namespace regolith::particles::lane_loads
