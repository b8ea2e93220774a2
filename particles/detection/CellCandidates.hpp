#pragma once
/// The candidate test of LinkedCells' pair sweep, one cell at a time and several candidates at
/// once: in 512-bit lanes where the build and the processor have AVX-512 (CellCandidatesLanes.cpp,
/// compiled with the lane code generation and without Eigen: GCC bug 105593,
/// cmake/RegolithTargets.cmake), one by one otherwise (also under valgrind, whose processor
/// has no AVX-512). Both give the same pairs in the same order with the same squared distances:
/// the lanes do the scalar test's IEEE operations in its order (no contraction).
#include <cstdint>
#include <span>
#include <vector>

namespace regolith::particles::cells_detail {

/// Spheres in structure-of-arrays lanes, single precision: centres relative to the grid's
/// origin and radii rounded up, as LinkedCells stores them (slot order).
struct SphereLanes {
    float const* x;
    float const* y;
    float const* z;
    float const* radius;
};

/// Slots [begin, end).
struct SlotRange {
    std::uint32_t begin;
    std::uint32_t end;
};

/// Two slots whose spheres may overlap, and the squared distance of their centres.
struct SlotPair {
    std::uint32_t s;
    std::uint32_t t;
    double d2;
};

/// Working storage of appendCellOverlaps, kept across cells so that it is allocated once.
struct CellScratch {
    std::vector<double> centres; ///< the cell's spheres in double: x, y, z, radius per slot
    /// The lanes' hits of one cell, as slot s, slot t and d2 (appendCellOverlapsInLanes).
    std::vector<std::uint32_t> s, t;
    std::vector<double> d2;
};

/// Appends to `out` the pairs of one cell's sweep whose spheres may overlap, d2 < (r_s + r_t +
/// slack)^2 with d2 = dx dx + dy dy + dz dz and d = x_t - x_s from the floats in double (exact
/// differences), in the scalar sweep's order: the cell's slots `own` with each other (for each
/// s, the t > s), then each range of `forward` in turn (each after `own`), for each
/// s of `own` the range's slots t ascending.
void appendCellOverlaps(SphereLanes const& lanes, SlotRange own, std::span<SlotRange const> forward,
                        double slack, CellScratch& scratch, std::vector<SlotPair>& out);

/// appendCellOverlaps one candidate at a time.
void appendCellOverlapsOneByOne(SphereLanes const& lanes, SlotRange own,
                                std::span<SlotRange const> forward, double slack,
                                std::vector<SlotPair>& out);

/// Whether the build compiled appendCellOverlapsInLanes for AVX-512 (CellCandidatesLanes.cpp).
[[nodiscard]] bool cellLanesCompiled();

/// Whether appendCellOverlapsInLanes runs here: the build has it and the processor AVX-512
/// (F, VL and DQ, the lane code generation's).
[[nodiscard]] bool cellLanesAvailable();

/// appendCellOverlaps in lanes. Pre: cellLanesAvailable().
void appendCellOverlapsInLanes(SphereLanes const& lanes, SlotRange own,
                               std::span<SlotRange const> forward, double slack,
                               CellScratch& scratch, std::vector<SlotPair>& out);

} // namespace regolith::particles::cells_detail
