#pragma once
/// The per-step overlap test of the Verlet list's pairs, a block of pairs at a time: the
/// fused contact loop (ContactDetector::listedPass) offers the pairs, their separations are
/// computed in structure-of-arrays lanes that the compiler vectorises, and the overlapping ones
/// are handed on in list order, from a list built without a branch per pair. Most listed pairs
/// of a gas do not touch, and in a packing of touching grains whether a pair touches is a coin
/// toss for the branch predictor; tested one by one with a branch, the test was a quarter of
/// the dense ramp's step. While whole blocks overlap (a static packing), pairs are tested one
/// by one after all: the branch is then predictable and the lanes would only add copies.
///
/// Same answer and same bits as PairRule.hpp's separation + overlapping for every pair: the
/// lanes do separation's operations in its order, and decide sqrt(d2) < reach with the
/// correctly rounded root, which `overlapping` reproduces without the root outside a thin band.
/// Either way the pairs reach onPair in the order offered. A pair offered as `ruled` (PairMode::
/// Check: near a block or domain face) reaches it only if the contact-point rule emits it too.
#include "core/math/Vec3.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace regolith::particles {

class OverlapScreen {
public:
    static constexpr std::size_t kCapacity = 64;

    /// `rule`: the contact-point rule of the pairs offered as ruled (none if null).
    explicit OverlapScreen(detection_detail::PairRule const* rule = nullptr)
        : m_rule(rule) {}

    /// Hands the listed pair (i, j) (canonical order) with its history hint to
    /// onPair(PairOverlap, hint), or with its kept spring to onPair(PairOverlap, *kept) if
    /// `kept` is not null, if it overlaps and, if `ruled`, the rule emits it: now, or at the
    /// flush that tests its block. Returns how many offered pairs this call found overlapping.
    template <class OnPair>
    [[gnu::always_inline]] std::size_t offer(ParticleStorage const& ps, core::Vec3 const& period,
                                             std::size_t i, std::size_t j, std::uint8_t& hint,
                                             KeptSpring* kept, OnPair& onPair, bool ruled = false) {
        assert(!ruled || m_rule != nullptr);
        if (m_direct) {
            auto const s = detection_detail::separation(ps, i, j, period);
            bool const hit = detection_detail::overlapping(s);
            if (hit && (!ruled || m_rule->emitsOverlapping(i, j)))
                handOn(onPair, PairOverlap{i, j, s.shiftJ}, &hint, kept);
            m_directHits += hit ? 1 : 0;
            if (++m_directSeen == kCapacity) { // back to blocks unless all of these overlapped
                m_direct = m_directHits == kCapacity;
                m_directSeen = m_directHits = 0;
            }
            return hit ? 1 : 0;
        }
        m_i[m_size] = static_cast<std::uint32_t>(i);
        m_j[m_size] = static_cast<std::uint32_t>(j);
        m_hint[m_size] = &hint;
        m_kept[m_size] = kept;
        m_ruled[m_size] = ruled;
        return ++m_size == kCapacity ? flush(ps, period, onPair) : 0;
    }

    /// Tests the pairs offered since the last flush and hands the overlapping ones on, in
    /// order (before a pair that bypasses the screen, and at the end of the list). Returns how
    /// many overlapped (the ruled ones the rule does not emit included).
    template <class OnPair>
    [[gnu::noinline]] std::size_t flush(ParticleStorage const& ps, core::Vec3 const& period,
                                        OnPair& onPair) {
        if (m_size == 0)
            return 0;
        std::size_t const overlaps = test(ps, period);
        m_direct = overlaps == kCapacity;
        for (std::size_t h = 0; h < overlaps; ++h) {
            std::size_t const k = m_hit[h];
            if (m_ruled[k] && !m_rule->emitsOverlapping(m_i[k], m_j[k]))
                continue;
            handOn(onPair, PairOverlap{m_i[k], m_j[k], core::Vec3(m_sx[k], m_sy[k], m_sz[k])},
                   m_hint[k], m_kept[k]);
        }
        m_size = 0;
        return overlaps;
    }

private:
    template <class OnPair>
    static void handOn(OnPair& onPair, PairOverlap const& p, std::uint8_t* hint, KeptSpring* kept) {
        if constexpr (std::is_invocable_v<OnPair&, PairOverlap const&, KeptSpring&>) {
            if (kept != nullptr) {
                onPair(p, *kept);
                return;
            }
        }
        onPair(p, *hint);
    }
    /// Fills the shifts of the offered pairs and lists the overlapping ones in m_hit,
    /// ascending; returns how many there are.
    std::size_t test(ParticleStorage const& ps, core::Vec3 const& period);

    using Lane = std::array<double, kCapacity>;
    std::size_t m_size = 0;
    std::array<std::uint32_t, kCapacity> m_i{};
    std::array<std::uint32_t, kCapacity> m_j{};
    std::array<std::uint8_t*, kCapacity> m_hint{};
    std::array<KeptSpring*, kCapacity> m_kept{}; ///< null for a pair without a kept spring
    std::array<bool, kCapacity> m_ruled{};       ///< the rule decides too (offer's `ruled`)
    detection_detail::PairRule const* m_rule;
    alignas(64) Lane m_xi, m_yi, m_zi, m_xj, m_yj, m_zj, m_reach;
    alignas(64) Lane m_sx, m_sy, m_sz; ///< shiftJ
    alignas(64) std::array<bool, kCapacity> m_overlap{};
    std::array<std::uint8_t, kCapacity> m_hit{}; ///< slots of the overlapping pairs
    bool m_direct = false;                       ///< testing pair by pair (see offer)
    std::size_t m_directSeen = 0; ///< pairs tested one by one since the last decision
    std::size_t m_directHits = 0; ///< and how many of them overlapped
};

} // namespace regolith::particles
