#pragma once
/// The per-step overlap test of the Verlet list's pairs, a block of pairs at a time: the
/// fused contact loop (ContactDetector::listedPass) hands over the live pairs of a block of the
/// list (VerletList::forEachNearBlock), their separations are computed in structure-of-arrays
/// lanes that the compiler vectorises, and the overlapping ones are handed on in list order,
/// from a bit mask of the block (a step per overlapping pair, no branch per pair tested). Most
/// listed pairs of a gas do not touch, and in a packing of touching grains whether a pair
/// touches is a coin toss for the branch predictor; tested one by one with a branch, the test
/// was a quarter of the dense ramp's step.
/// A static packing, where whole blocks overlap, is tested in the lanes too: one by one there
/// (the branch predictable) the contact phase of the MESA-PD lattice took 1.05x as long.
///
/// Same answer and same bits as PairRule.hpp's separation + overlapping for every pair: the
/// lanes do separation's operations in its order, and decide sqrt(d2) < reach with the
/// correctly rounded root, which `overlapping` reproduces without the root outside a thin band.
/// The pairs reach the caller in the order given.
#include "core/math/Vec3.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace regolith::particles {

class OverlapScreen {
public:
    static constexpr std::size_t kCapacity = 64;
    static_assert(kCapacity == 64, "lanes collects the overlapping slots in one 64-bit mask");

    /// Tests the pairs (i[k], j[k]), k < n <= kCapacity (storage indices, canonical order),
    /// and calls onHit(k, PairOverlap) for each overlapping one, in order. Returns how many
    /// overlapped. `oneImage`: the caller knows that the two copies of every pair are in the
    /// same periodic image (their shiftJ is zero; the images are not read).
    template <class OnHit>
    std::size_t test(ParticleStorage const& ps, core::Vec3 const& period, std::uint32_t const* i,
                     std::uint32_t const* j, std::size_t n, OnHit&& onHit, bool oneImage = false) {
        assert(n <= kCapacity);
        std::size_t const hits = lanes(ps, period, i, j, n, oneImage);
        for (std::size_t h = 0; h < hits; ++h) {
            std::size_t const k = m_hit[h];
            onHit(k, PairOverlap{i[k], j[k],
                                 oneImage ? core::Vec3::Zero()
                                          : core::Vec3(m_sx[k], m_sy[k], m_sz[k])});
        }
        return hits;
    }

private:
    /// Fills the shifts of the pairs and lists the overlapping ones in m_hit, ascending;
    /// returns how many there are.
    std::size_t lanes(ParticleStorage const& ps, core::Vec3 const& period, std::uint32_t const* i,
                      std::uint32_t const* j, std::size_t n, bool oneImage);

    using Lane = std::array<double, kCapacity>;
    alignas(64) Lane m_xi, m_yi, m_zi, m_xj, m_yj, m_zj, m_reach;
    alignas(64) Lane m_sx, m_sy, m_sz;                   ///< shiftJ
    alignas(64) std::array<bool, kCapacity> m_overlap{}; ///< read eight at a time
    std::array<std::uint8_t, kCapacity> m_hit{};         ///< slots of the overlapping pairs
};

} // namespace regolith::particles
