// appendCellOverlapsInLanes (CellCandidates.hpp): compiled with the lane code generation
// (cmake/RegolithTargets.cmake); without AVX-512 in the build, cellLanesCompiled() says so.
#include "particles/detection/CellCandidates.hpp"

#include <algorithm>

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

namespace regolith::particles::cells_detail {

#if defined(__AVX512F__) && defined(__AVX512VL__)

namespace {

/// One sphere s, broadcast to every lane, in double.
struct Centre {
    __m512d x, y, z, radius;
};

/// The sphere whose x, y, z, radius in double are at `c`.
Centre centreAt(double const* c) {
    return {_mm512_set1_pd(c[0]), _mm512_set1_pd(c[1]), _mm512_set1_pd(c[2]), _mm512_set1_pd(c[3])};
}

/// Up to eight floats from `p` (lanes beyond `live` neither read nor faulted on), in double.
/// The full-width conversion of GCC 12's headers trips its false maybe-uninitialized warning
/// (bug 105593); the zero-masked one is the same instruction.
__m512d load(float const* p, __mmask8 live) {
    return _mm512_maskz_cvtps_pd(0xFF, _mm256_maskz_loadu_ps(live, p));
}

/// The lanes of `live` (candidates at x, y, z, radius + k) that may overlap `a`, and every
/// lane's squared distance in `d2` (the scalar test's operations, in its order).
__mmask8 test(Centre const& a, SphereLanes const& candidates, std::uint32_t k, __mmask8 live,
              __m512d slack, __m512d& d2) {
    __m512d const dx = _mm512_sub_pd(load(candidates.x + k, live), a.x);
    __m512d const dy = _mm512_sub_pd(load(candidates.y + k, live), a.y);
    __m512d const dz = _mm512_sub_pd(load(candidates.z + k, live), a.z);
    d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                       _mm512_mul_pd(dz, dz));
    __m512d const reach =
        _mm512_add_pd(_mm512_add_pd(a.radius, load(candidates.radius + k, live)), slack);
    return _mm512_mask_cmp_pd_mask(live, d2, _mm512_mul_pd(reach, reach), _CMP_LT_OQ);
}

__mmask8 firstLanes(std::uint32_t n) {
    return static_cast<__mmask8>(n >= 8 ? 0xFFU : (1U << n) - 1U);
}

} // namespace

bool cellLanesCompiled() {
    return true;
}

void appendCellOverlapsInLanes(SphereLanes const& lanes, SlotRange own,
                               std::span<SlotRange const> forward, double slack,
                               CellScratch& scratch, std::vector<SlotPair>& out) {
    __m512d const slackLanes = _mm512_set1_pd(slack);
    __m512d d2;
    // The cell's spheres broadcast once (a cell holds a few), then range by range as the
    // scalar sweep: for each s, the range's slots in lanes of eight.
    std::uint32_t const members = own.end - own.begin;
    scratch.centres.resize(4 * std::size_t{members});
    for (std::uint32_t m = 0; m < members; ++m) {
        std::uint32_t const s = own.begin + m;
        double* const c = &scratch.centres[4 * std::size_t{m}];
        c[0] = static_cast<double>(lanes.x[s]);
        c[1] = static_cast<double>(lanes.y[s]);
        c[2] = static_cast<double>(lanes.z[s]);
        c[3] = static_cast<double>(lanes.radius[s]);
    }
    // The hits in the sweep's order, without a branch per hit: each block's lanes compressed
    // in registers (a compressing store to memory is microcoded on Zen 4) and stored whole at
    // the count so far, the lanes past the hits overwritten by the next block's; appended to
    // `out` whenever one more sphere's sweep of a range (and a block's eight lanes past its
    // hits) might not fit.
    std::size_t longest = members;
    for (SlotRange const& r : forward)
        longest = std::max<std::size_t>(longest, r.end - r.begin);
    std::size_t const room = std::max<std::size_t>(1024, 2 * (longest + 8));
    if (scratch.t.size() < room) {
        scratch.s.resize(room);
        scratch.t.resize(room);
        scratch.d2.resize(room);
    }
    std::uint32_t* const ss = scratch.s.data();
    std::uint32_t* const ts = scratch.t.data();
    double* const ds = scratch.d2.data();
    std::size_t count = 0;
    auto const flush = [&] {
        for (std::size_t k = 0; k < count; ++k)
            out.push_back({ss[k], ts[k], ds[k]});
        count = 0;
    };
    __m256i const laneIndex = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    auto each = [&](std::uint32_t t0, std::uint32_t t1) {
        for (std::uint32_t m = 0; m < members; ++m) {
            if (count + (t1 - t0) + 8 > room)
                flush();
            std::uint32_t const s = own.begin + m;
            Centre const a = centreAt(&scratch.centres[4 * std::size_t{m}]);
            __m256i const sLanes = _mm256_set1_epi32(static_cast<int>(s));
            // 64-bit: t1 may lie within a block of eight of the slots' 32-bit limit.
            for (std::uint64_t block = std::max(t0, s + 1); block < t1; block += 8) {
                auto const t = static_cast<std::uint32_t>(block);
                __mmask8 const hit = test(a, lanes, t, firstLanes(t1 - t), slackLanes, d2);
                __m256i const tLanes =
                    _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(t)), laneIndex);
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(ss + count), sLanes);
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(ts + count),
                                    _mm256_maskz_compress_epi32(hit, tLanes));
                _mm512_storeu_pd(ds + count, _mm512_maskz_compress_pd(hit, d2));
                count += static_cast<std::size_t>(__builtin_popcount(hit));
            }
        }
    };
    each(own.begin, own.end);
    for (SlotRange const& r : forward)
        each(r.begin, r.end);
    flush();
}

#else

bool cellLanesCompiled() {
    return false;
}

void appendCellOverlapsInLanes(SphereLanes const& lanes, SlotRange own,
                               std::span<SlotRange const> forward, double slack,
                               CellScratch& /*scratch*/, std::vector<SlotPair>& out) {
    appendCellOverlapsOneByOne(lanes, own, forward, slack, out);
}

#endif

} // namespace regolith::particles::cells_detail
