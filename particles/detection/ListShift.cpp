/// A Verlet list that follows a drift (ContactDetector's class comment, "A list that follows a
/// drift"): at a detect after which the step's motion could bring a copy to skin / 2 from its
/// reference, the positions are compared; where the copies moved together, the references
/// move by their common drift and the pairs are settled again, which keeps the pairs found
/// and the springs of the pairs deep inside the block. Before the synchronisation, whether a
/// kept spring must go back to the histories.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

// VerletList::resettle, a template whose one user is shiftList below.
template <class S, class D>
void VerletList::resettle(S&& unchanged, D&& decide) {
    // In place: the pairs keep their places (a parked one leaves a hole that forEachPair
    // skips, as a dead one), the revived ones are appended.
    m_parkedAgain.clear();
    auto const count = [&](PairMode m) {
        m_owned += m != PairMode::Check ? 1 : 0;
        m_kept += keepsSpring(m) ? 1 : 0;
        m_pressed += isPressed(m) ? 1 : 0;
    };
    std::size_t const listed = m_pairs.size();
    for (std::size_t p = 0; p < listed; ++p) {
        auto& pair = m_pairs[p];
        if (unchanged(pair[0], pair[1]) || m_indexOf[pair[0]] == kDead ||
            m_indexOf[pair[1]] == kDead)
            continue; // (in that order: most pairs are unchanged)
        KeptSpring spare{};
        KeptSpring& spring = p < m_springs.size() ? m_springs[p] : spare;
        int const mode = decide(pair[0], pair[1], m_shift[p], true, m_mode[p], spring, m_hint[p]);
        if (mode == kDrop) {
            m_parkedAgain.push_back({pair, m_shift[p]});
            pair[0] = m_hole;
            m_live.stale = true; // a hole the walk skips (a mode changed in place: no change)
            continue;
        }
        auto const m = static_cast<PairMode>(mode);
        if (m != m_mode[p])
            count(m);
        m_mode[p] = m;
        if (keepsSpring(m) && p >= m_springs.size()) {
            m_springs.resize(m_pairs.size()); // parallel to the pairs from the first kept one
            m_springs[p] = spare;
        }
    }
    for (auto parked : m_parked) {
        auto& pair = parked.pair;
        if (m_indexOf[pair[0]] == kDead || m_indexOf[pair[1]] == kDead)
            continue;
        KeptSpring spring{};
        std::uint8_t hint = 0;
        int const mode =
            decide(pair[0], pair[1], parked.shift, false, PairMode::Check, spring, hint);
        if (mode == kDrop) {
            m_parkedAgain.push_back(parked);
            continue;
        }
        auto const m = static_cast<PairMode>(mode);
        count(m);
        // Its copies live (tested above): the walk's arrays take it at the end, where
        // refreshLive would put it.
        m_live.a.push_back(m_indexOf[pair[0]]);
        m_live.b.push_back(m_indexOf[pair[1]]);
        m_live.at.push_back(static_cast<std::uint32_t>(m_pairs.size()));
        m_pairs.push_back(pair);
        m_shift.push_back(parked.shift);
        m_gap.push_back(kNoGap);
        m_mode.push_back(m);
        m_hint.push_back(hint);
        if (!m_springs.empty() || keepsSpring(m)) {
            m_springs.resize(m_pairs.size() - 1);
            m_springs.push_back(spring);
        }
    }
    m_parked.swap(m_parkedAgain);
}

void ContactDetector::beforeSync(ParticleStorage& ps, double movedAtMost) {
    if (!listed() || m_config.sortByUid || !m_list.mayMoveTooFar(movedAtMost))
        return;
    // The list names every copy (nothing changed the storage since the last detect). The
    // masters have moved, and no more in the synchronisation: if none is the budget from its
    // reference, none of a kept pair leaves the block (it lies deeper), and the next detect
    // decides, with every copy where the synchronisation put it (shiftAhead).
    if (!m_spreadOut && m_list.followsUnchanged(ps) && std::isfinite(movedAtMost) &&
        movedAtMost >= 0.0) {
        VerletList::Displacements const d = m_list.displacements(ps);
        if (d.finite && d.largestMaster * (1.0 + 1e-9) < m_list.budget())
            return;
    }
    writeBackLeaving(ps); // the next detect rebuilds (carrying the springs) or shifts
}

void ContactDetector::shiftAhead(ParticleStorage& ps, double moved) {
    // The step's motion again would bring the list to its budget: measured now, while every
    // copy is where the synchronisation put it (before the sync the shadows lag a step).
    if (!m_spreadOut && std::isfinite(moved) && moved >= 0.0 && m_list.mayMoveTooFar(2.0 * moved))
        followDrift(ps, moved);
}

void ContactDetector::followDrift(ParticleStorage& ps, double motion) {
    VerletList::Displacements const d = m_list.displacements(ps);
    if (!d.finite)
        return; // movedTooFar finds it
    m_list.setCommonDisplacement(d.drift);
    double const half = m_list.budget();
    double const rounding = 1.0 + 1e-9; // the sums' rounding, as VerletList's tests
    if ((d.largest + motion) * rounding < half) {
        m_list.setMoved(d.largest); // the bound restarts from the comparison
        return;
    }
    double const spread = m_list.spread(ps, d.drift);
    double const room = kShiftSpread * half - (spread + motion) * rounding;
    if (!(room > 0.0)) {
        m_spreadOut = true; // until the rebuild it soon needs: no more comparisons for a shift
        return;
    }
    // The references lead the copies along their drift, by as far as they drifted (within
    // the room): a steady drift then carries the copies through their references and as far
    // beyond before the next shift, twice as long as from references where they stand.
    double const drifted = d.drift.norm();
    core::Vec3 const lead = drifted > 0.0 ? core::Vec3(std::min(room, drifted) / drifted * d.drift)
                                          : core::Vec3::Zero();
    shiftList(ps, d.drift + lead, spread + lead.norm());
}

void ContactDetector::shiftList(ParticleStorage& ps, core::Vec3 const& drift, double spread) {
    ++m_shifts;
    double const rounding = 4.0 * m_stats.slack + m_list.referenceSlack(); // classifyListed's
    m_list.shift(drift, spread);
    core::Vec3 const shifted = m_list.drift().cwiseAbs();
    m_depths.setShifted(shifted);
    // The rebuild's copies deeper inside the block than settledDepth along every axis, less
    // the list's shift along it: a pair of two of them is emitted whenever it overlaps, and
    // settledMode answers as before (its other conditions do not depend on where the pair
    // lies), so it is not settled again. Arrivals have no depth.
    double const depth = settledDepth(rounding);
    std::size_t const built = m_list.builtSize();
    m_deepIds.resize(built);
    for (std::size_t id = 0; id < built; ++id) {
        ReferenceDepths::Axes const& d =
            m_depths.ofAxes(m_list, ps, static_cast<VerletList::Id>(id));
        m_deepIds[id] =
            d[0] > depth + shifted.x() && d[1] > depth + shifted.y() && d[2] > depth + shifted.z();
    }
    std::uint8_t const* const deep = m_deepIds.data();
    auto const unchanged = [deep, built](VerletList::Id a, VerletList::Id b) {
        return a < built && b < built && (deep[a] & deep[b]) != 0;
    };
    m_list.resettle(unchanged, [&](VerletList::Id& a, VerletList::Id& b, CopyImage& shift,
                                   bool listed, PairMode was, KeptSpring& spring,
                                   std::uint8_t& hint) {
        if (listed && was == PairMode::Check)
            return static_cast<int>(PairMode::Check); // the rule per step holds in any frame
        std::size_t ka = 0, kb = 0;
        int const mode =
            settlePair(ps, a, b, shift, ka, kb, m_listRegion, m_listFrame, rounding).mode;
        // A spring beside the list goes back to the history, or comes from it, where the
        // pair's mode changes (the canonical i's history: settlePair ordered ka, kb).
        bool const had = listed && keepsSpring(was);
        bool const has = mode != VerletList::kDrop && keepsSpring(static_cast<PairMode>(mode));
        if (m_springsLive && had && !has)
            writeBackSpring(ps, ka, ps.uid(kb), spring, hint);
        else if (m_springsLive && has && !had)
            spring = springFromHistory(ps, ka, kb, hint);
        return mode;
    });
}

} // namespace regolith::particles
