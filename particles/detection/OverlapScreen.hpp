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
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace regolith::particles {

class OverlapScreen {
public:
    static constexpr std::size_t kCapacity = 64;
    static_assert(kCapacity == 64, "lanes collects the overlapping slots in one 64-bit mask");

    /// Tests the pairs (i[k], j[k]), k < n <= kCapacity (storage indices, canonical order),
    /// and calls onHit(k, PairOverlap) for each overlapping one that `select` keeps, in order:
    /// select(overlapping) gets the overlapping pairs as bit k for pair k and returns those to
    /// hand on (it may call ruled()). Returns how many overlapped. `oneImage`: the caller knows
    /// that the two copies of every pair are in the same periodic image (their shiftJ is zero;
    /// the images are not read).
    template <class OnHit, class Select>
    std::size_t test(ParticleStorage const& ps, core::Vec3 const& period, std::uint32_t const* i,
                     std::uint32_t const* j, std::size_t n, OnHit&& onHit, Select&& select,
                     bool oneImage = false, CopyImage const* shifts = nullptr) {
        assert(n <= kCapacity);
        std::uint64_t const overlapping = lanes(ps, period, i, j, n, oneImage, shifts);
        for (std::uint64_t hits = select(overlapping); hits != 0; hits &= hits - 1) {
            auto const k = static_cast<std::size_t>(std::countr_zero(hits));
            onHit(k, PairOverlap{i[k], j[k],
                                 oneImage ? core::Vec3::Zero()
                                          : core::Vec3(m_sx[k], m_sy[k], m_sz[k])});
        }
        return static_cast<std::size_t>(std::popcount(overlapping));
    }
    /// The overlapping pairs of (i[k], j[k]), k < n <= kCapacity, bit k for pair k, for a
    /// caller that hands them on itself (`oneImage` as in test()).
    std::uint64_t overlapping(ParticleStorage const& ps, core::Vec3 const& period,
                              std::uint32_t const* i, std::uint32_t const* j, std::size_t n,
                              bool oneImage) {
        assert(n <= kCapacity);
        return lanes(ps, period, i, j, n, oneImage, nullptr);
    }
    /// test() handing on every overlapping pair.
    template <class OnHit>
    std::size_t test(ParticleStorage const& ps, core::Vec3 const& period, std::uint32_t const* i,
                     std::uint32_t const* j, std::size_t n, OnHit&& onHit, bool oneImage = false) {
        return test(
            ps, period, i, j, n, onHit, [](std::uint64_t all) { return all; }, oneImage);
    }

    /// PairRule::emitsOverlapping for the pairs `pairs` (bit k for pair k) of the test() under
    /// way with images (not `oneImage`; i, j as given to it), in lanes: bit k set where
    /// neither copy of pair k is Fixed and its ownership point lies in `region` in the pair's
    /// own image instance. Bit k of `unsure` is set where the lanes do not decide (the point
    /// not finite, or two periods or more outside the domain, where PairRule may throw): the
    /// caller rules on those with PairRule. Elsewhere the same decision as PairRule from the
    /// same bits: the lanes do overlapGeometry's and owns' operations in their order, and take
    /// wrapOnAxis's image as the interval between its boundaries.
    std::uint64_t ruled(ParticleStorage const& ps, core::AABB const& region,
                        PeriodicFrame const& frame, std::uint32_t const* i, std::uint32_t const* j,
                        std::uint64_t pairs, std::uint64_t& unsure);

private:
    /// Fills the shifts of the pairs (the images' difference, plus shifts[k] where given: the
    /// pairs' own across wrapped faces, VerletList::shift) and returns the overlapping ones,
    /// bit k for pair k.
    std::uint64_t lanes(ParticleStorage const& ps, core::Vec3 const& period, std::uint32_t const* i,
                        std::uint32_t const* j, std::size_t n, bool oneImage,
                        CopyImage const* shifts);

    using Lane = std::array<double, kCapacity>;
    alignas(64) Lane m_xi, m_yi, m_zi, m_xj, m_yj, m_zj, m_reach;
    alignas(64) Lane m_sx, m_sy, m_sz;                   ///< shiftJ
    alignas(64) std::array<bool, kCapacity> m_overlap{}; ///< read eight at a time
    /// ruled()'s pairs, packed: their slots in the block, the centres (j's shifted), the
    /// reach and radii, -image(i) per axis, both Fixed (1 or 0), and the results (1 or 0).
    struct RuleLanes {
        std::array<std::uint8_t, kCapacity> slot;
        alignas(64) std::array<Lane, 3> xi, xj, target;
        alignas(64) Lane reach, ri, rj, fixed, emit, sure;
    };
    RuleLanes m_rule;
};

} // namespace regolith::particles
