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
    // A consumer that computes the geometry itself gets the listed pairs screened a block at
    // a time (OverlapScreen; those that keep the rule, PairMode::Check, ruled on there too),
    // those known to overlap (KeptPressed) untested; a pair that bypasses the screen first
    // flushes the block, so that every pair still reaches onPair in list order. Always
    // inlined into the list's loop: left to itself, the compiler kept it out of line for some
    // models (the per-contact Hertz loop ran 2 % more instructions).
    OverlapScreen screen(&rule);
    if constexpr (TakesPairOverlaps<OnPair>) // the screen decides overlap, not the range
        if (!keepPairs && range != 0.0)
            throw core::Error("contact detection: a pair callback that takes overlaps only "
                              "needs a contact model acting in overlap only (range 0)");
    auto eachPair = [&](std::size_t a, std::size_t b, std::size_t p)
        __attribute__((always_inline)) {
        PairMode const mode = m_list.mode(p);
        KeptSpring* const kept = m_springsLive && keepsSpring(mode) ? &m_list.spring(p) : nullptr;
        if (kept != nullptr)
            m_list.prefetchSpring(p + 16); // read in list order: a stream from memory
        if constexpr (TakesPairOverlaps<OnPair>) {
            if (!keepPairs) {
                if constexpr (TakesKeptSprings<OnPair>) {
                    if (isPressed(mode) && kept != nullptr) { // overlaps: no test
                        overlaps += screen.flush(ps, period, onPair) + 1;
                        onPair.kept(a, b, *kept);
                        return;
                    }
                }
                overlaps += screen.offer(ps, period, a, b, m_list.hint(p), kept, onPair,
                                         mode == PairMode::Check);
                return;
            }
        }
        if (mode != PairMode::Check) {
            if (!detection_detail::overlapGeometry(ps, a, b, period, c, range))
                return;
            ++overlaps;
        } else {
            // A cheap rejection first (most listed pairs are apart), generous by the slack:
            // the rule decides exactly.
            core::Vec3 d = x[b] - x[a];
            if (!sameImage(ps.image(a), ps.image(b)))
                d += imageOffset(detection_detail::imageDifference(ps.image(b), ps.image(a)),
                                 period);
            double const reach = ps.radius(a) + ps.radius(b) + rangeSlack;
            if (!(d.squaredNorm() < reach * reach) || !rule(a, b, c))
                return;
        }
        if (keepPairs)
            out.pairs.push_back(c);
        detection_detail::handOver(onPair, c, m_list.hint(p), kept);
    };
    m_list.forEachNearPair(eachPair);
    if constexpr (TakesPairOverlaps<OnPair>)
        overlaps += screen.flush(ps, period, onPair);
    m_stats.overlapsFound += overlaps;
}

} // namespace regolith::particles
