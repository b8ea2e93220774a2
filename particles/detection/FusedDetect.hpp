#pragma once
/// ContactDetector's fused detect, where detection and evaluation are one loop: the member
/// templates detect(..., onPair, keepPairs) and listedPass, the per-step pass over the Verlet
/// list's settled pairs (ContactDetector, "Settled pairs and the fused loop"). Inline, in a
/// header, because every contact model instantiates them with its own callback. Included by
/// ContactDetector.hpp, after the class; include that one.
#include "core/Error.hpp"
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/OverlapScreen.hpp"
#include "particles/detection/PairCallbacks.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace regolith::particles {

template <class OnPair>
void ContactDetector::detect(ParticleStorage& ps, WallList const& walls, core::AABB const& region,
                             PeriodicFrame const& frame, ContactList& out, OnPair&& onPair,
                             bool keepPairs) {
    if (!listed() || m_config.sortByUid) {
        detect(ps, walls, region, frame, out);
        for (Contact const& c : out.pairs) {
            std::uint8_t hint = 0;
            detection_detail::handOver(onPair, c, hint);
        }
        return;
    }
    out.clear();
    updateList(ps, region, frame);
    if constexpr (TakesKeptSprings<std::remove_cvref_t<OnPair>>) {
        if (m_config.keepSprings) { // only a callback that takes them: the others see histories
            fillKeptSprings(ps, m_fillFrom);
            m_pass = onPair.pass();
        }
    }
    writeBackCarried(ps); // a callback without kept springs reads the histories
    listedPass(ps, region, frame, out, onPair, keepPairs);
    wallPass(ps, walls, out);
}

template <class OnPair>
void ContactDetector::listedPass(ParticleStorage const& ps, core::AABB const& region,
                                 PeriodicFrame const& frame, ContactList& out, OnPair&& onPair,
                                 bool keepPairs) {
    detection_detail::PairRule const rule(ps, region, frame, m_stats, m_config.range);
    core::Vec3 const& period = rule.period();
    double const slack = m_stats.slack;
    double const range = m_config.range; // in a register: the loop's stores may alias m_config
    double const rangeSlack = range + slack;
    auto const& x = ps.positions();
    std::size_t overlaps = 0;
    Contact c;
    // A consumer that computes the geometry itself gets the listed pairs screened a block of
    // the list at a time (OverlapScreen), those that keep the rule (PairMode::Check) ruled on
    // where they overlap; every pair reaches onPair in list order.
    if constexpr (TakesPairOverlaps<OnPair>) {
        if (!keepPairs) {
            if (range != 0.0)
                throw core::Error("contact detection: a pair callback that takes overlaps only "
                                  "needs a contact model acting in overlap only (range 0)");
            static_assert(OverlapScreen::kCapacity >= VerletList::kBlock);
            OverlapScreen screen;
            bool const springsLive = m_springsLive;
            // Pairs known to overlap while the list holds (KeptPressed: two masters, one
            // image) are handed on untested, in their places among the tested ones.
            bool const pressedListed =
                TakesKeptSprings<OnPair> && springsLive && m_list.numPressed() != 0;
            PairMode const* const modes = m_list.modes().data();
            // The pairs' own shifts across the wrapped faces, gathered per block where any.
            CopyImage const* const pairShifts =
                frame.anyWrapped() ? m_list.shifts().data() : nullptr;
            std::array<CopyImage, VerletList::kBlock> blockShifts;
            std::uint8_t* const hints = m_list.hints().data();
            KeptSpring* const springs = m_list.springs().data();
            m_list.forEachNearBlock([&](std::uint32_t const* a, std::uint32_t const* b,
                                        std::uint32_t const* at, std::size_t n) {
                // Every pair handed on is one this block evaluates (the rule applied).
                auto const handOn = [&](std::size_t k, PairOverlap const& o)
                    __attribute__((always_inline)) {
                    std::size_t const p = at[k];
                    if constexpr (TakesKeptSprings<OnPair>) {
                        if (springsLive && keepsSpring(modes[p])) {
                            onPair(o, springs[p]);
                            return;
                        }
                    }
                    onPair(o, hints[p]);
                };
                // Of the overlapping pairs among those screened (ti[t], tj[t], the list's pair
                // listed[t]; bit t), the ones this block evaluates: the pairs that keep the
                // rule (PairMode::Check) ruled on in the screen's lanes, all at once
                // (OverlapScreen::ruled). Ruled one by one, each waited on its root and
                // divisions and on a branch that is a coin toss: the two image instances of a
                // pair across a periodic face take turns.
                auto const evaluated = [&](std::uint64_t overlapping, std::uint32_t const* ti,
                                           std::uint32_t const* tj, std::uint32_t const* listed,
                                           std::size_t m) {
                    std::uint64_t check = 0;
                    for (std::size_t t = 0; t < m; ++t)
                        check |= std::uint64_t{modes[listed[t]] == PairMode::Check} << t;
                    std::uint64_t const contested = overlapping & check;
                    if (contested == 0)
                        return overlapping;
                    std::uint64_t unsure = 0;
                    std::uint64_t const owned =
                        screen.ruled(ps, region, frame, ti, tj, contested, unsure);
                    std::uint64_t keep = (overlapping & ~check) | (owned & ~unsure);
                    for (std::uint64_t u = contested & unsure; u != 0; u &= u - 1) {
                        auto const t = static_cast<std::size_t>(std::countr_zero(u));
                        CopyImage const shift =
                            pairShifts != nullptr ? pairShifts[listed[t]] : kNoImage;
                        if (rule.emitsOverlapping(ti[t], tj[t], shift))
                            keep |= std::uint64_t{1} << t;
                    }
                    return keep;
                };
                // A block of Kept pairs only (most blocks of a packing's list, whose kept
                // pairs lead it) is handed on without a mode test per overlapping pair: that
                // test's dependent loads sat on the hand-over's path. Its pairs join two
                // masters at image zero (staysInBlock), so the screen skips their images.
                if constexpr (TakesKeptSprings<OnPair>) {
                    bool kept = springsLive;
                    for (std::size_t k = 0; k < n; ++k)
                        kept &= modes[at[k]] == PairMode::Kept;
                    if (kept) {
                        std::uint64_t const hits = screen.overlapping(ps, period, a, b, n, true);
                        overlaps += static_cast<std::size_t>(std::popcount(hits));
                        detection_detail::handOverKeptHits(onPair, a, b, at, hits, springs);
                        return;
                    }
                }
                if (pairShifts != nullptr)
                    for (std::size_t k = 0; k < n; ++k)
                        blockShifts[k] = pairShifts[at[k]];
                CopyImage const* const shifts =
                    pairShifts != nullptr ? blockShifts.data() : nullptr;
                if (!pressedListed) {
                    overlaps += screen.test(
                        ps, period, a, b, n, handOn,
                        [&](std::uint64_t o) { return evaluated(o, a, b, at, n); }, false, shifts);
                    return;
                }
                std::array<bool, VerletList::kBlock> pressed;
                std::array<std::uint32_t, VerletList::kBlock> slot, ta, tb, tat;
                std::array<CopyImage, VerletList::kBlock> tsh;
                std::size_t tested = 0;
                for (std::size_t k = 0; k < n; ++k) {
                    pressed[k] = isPressed(modes[at[k]]);
                    slot[tested] = static_cast<std::uint32_t>(k);
                    ta[tested] = a[k];
                    tb[tested] = b[k];
                    tat[tested] = at[k];
                    tsh[tested] = shifts != nullptr ? shifts[k] : kNoImage;
                    tested += pressed[k] ? 0 : 1;
                }
                std::size_t next = 0; // the block's first pair not yet handed on or passed
                auto const pressedUpTo = [&](std::size_t end) {
                    for (; next < end; ++next)
                        if (pressed[next]) {
                            handOn(next, PairOverlap{a[next], b[next], core::Vec3::Zero()});
                            ++overlaps;
                        }
                };
                if (tested != 0)
                    overlaps += screen.test(
                        ps, period, ta.data(), tb.data(), tested,
                        [&](std::size_t t, PairOverlap const& o) __attribute__((always_inline)) {
                            pressedUpTo(slot[t]);
                            next = slot[t] + 1;
                            handOn(slot[t], o);
                        },
                        [&](std::uint64_t o) {
                            return evaluated(o, ta.data(), tb.data(), tat.data(), tested);
                        },
                        false, shifts != nullptr ? tsh.data() : nullptr);
                pressedUpTo(n);
            });
            m_stats.overlapsFound += overlaps;
            return;
        }
    }
    // Else pair by pair, the geometry computed here and handed over as a Contact.
    auto eachPair = [&](std::size_t a, std::size_t b, std::size_t p)
        __attribute__((always_inline)) {
        PairMode const mode = m_list.mode(p);
        KeptSpring* const kept = m_springsLive && keepsSpring(mode) ? &m_list.spring(p) : nullptr;
        CopyImage const& shift = m_list.shift(p);
        if (mode != PairMode::Check) {
            if (!detection_detail::overlapGeometry(ps, a, b, period, c, range, shift))
                return;
            ++overlaps;
        } else {
            // A cheap rejection first (most listed pairs are apart), generous by the slack:
            // the rule decides exactly.
            core::Vec3 d = x[b] - x[a];
            if (!sameImage(ps.image(a), ps.image(b)) || !isZero(shift))
                d += imageOffset(detection_detail::imageDifference(ps.image(b), ps.image(a), shift),
                                 period);
            double const reach = ps.radius(a) + ps.radius(b) + rangeSlack;
            if (!(d.squaredNorm() < reach * reach) || !rule(a, b, c, shift))
                return;
        }
        if (keepPairs)
            out.pairs.push_back(c);
        detection_detail::handOver(onPair, c, m_list.hint(p), kept);
    };
    m_list.forEachNearPair(eachPair);
    m_stats.overlapsFound += overlaps;
}

} // namespace regolith::particles
