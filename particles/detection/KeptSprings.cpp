/// The tangential springs the Verlet list keeps beside its settled pairs deep inside the block
/// (ContactDetector's class comment, "Springs kept beside the list"): which pairs keep one,
/// how they are filled from the grains' histories, written back, and counted where they live.
#include "core/Error.hpp"
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

namespace regolith::particles {

bool ContactDetector::staysInBlock(ParticleStorage const& ps, std::size_t ka, std::size_t kb,
                                   VerletList::Id a, VerletList::Id b, core::AABB const& region,
                                   PeriodicFrame const& frame, double rounding) const {
    // Two masters at image zero: the only copies of their grains that move them, and those
    // whose histories a kept spring belongs to (the canonical i's).
    if (!ps.flags(ka).isMaster() || !ps.flags(kb).isMaster() || !isZero(ps.image(ka)) ||
        !isZero(ps.image(kb)))
        return false;
    // Deeper than skin / 2 inside the block, both: while the list holds (no copy moves skin / 2
    // from its reference) neither leaves the block, so the synchronisation neither migrates
    // nor wraps them.
    // (The depths from the region's faces, with the rounding once more, answer for most pairs:
    // the region holds the box they are measured in.)
    double const depth = listMotion(rounding);
    if (!m_depths.deeperThan(m_list, ps, a, b, depth + rounding))
        for (VerletList::Id id : {a, b}) {
            core::Vec3 const x = m_list.reference(id);
            for (int d = 0; d < 3; ++d)
                if (!(x[d] - depth > region.min[d] && x[d] + depth < region.max[d]))
                    return false;
        }
    return oneImageInstance(ps.radius(ka) + ps.radius(kb), frame, rounding);
}

PairMode ContactDetector::settledMode(ParticleStorage const& ps, std::size_t ka, std::size_t kb,
                                      VerletList::Id a, VerletList::Id b, bool stays,
                                      double rounding) const {
    if (!m_config.keepSprings || !stays)
        return PairMode::Owned;
    double const reach = ps.radius(ka) + ps.radius(kb);
    bool const pressed = pressedWhileListed(
        (m_list.reference(b) - m_list.reference(a)).squaredNorm(), reach, rounding);
    return pressed ? PairMode::KeptPressed : PairMode::Kept;
}

double ContactDetector::listMotion(double rounding) const {
    return 0.5 * m_listSkin + m_list.referenceSlack() + rounding;
}

bool ContactDetector::oneImageInstance(double reach, PeriodicFrame const& frame,
                                       double rounding) const {
    // Two instances' reference separations would both lie below the listing reach r_i + r_j +
    // skin (+ rounding), and each centre moves less than skin / 2 meanwhile, so their images
    // would be less than 2 (r_i + r_j + 2 skin) apart.
    double const twice = 2.0 * (reach + 2.0 * m_listSkin + rounding);
    core::Vec3 const period = frame.period();
    for (std::size_t d = 0; d < 3; ++d)
        if (frame.periodic[d] && !(period[static_cast<int>(d)] > twice))
            return false;
    return true;
}

bool ContactDetector::pressedWhileListed(double apart2, double reach, double rounding) const {
    // Each centre stays within skin / 2 of its reference (and that within the reference slack
    // of the stored one), so the distance stays below the references' `apart` + skin + 2
    // slacks; the relative 1e-9 covers the rounding of the test in the lanes (PairRule.hpp's
    // overlapping, sqrt(d2) < r_a + r_b).
    double const within = reach * (1.0 - 1e-9);
    double const moves = m_listSkin + 2.0 * m_list.referenceSlack() + rounding;
    // Most listed pairs stand farther apart than `within` less `moves` by far more than any
    // rounding: no root for them (the sums below only grow with `apart`).
    double const limit = within - moves;
    if (limit > 1e-6 * within && apart2 > limit * limit * (1.0 + 1e-6))
        return false;
    // (Summed from the root on, not as root + moves: the decision as before, bit for bit.)
    return std::sqrt(apart2) + m_listSkin + 2.0 * m_list.referenceSlack() + rounding < within;
}

void ContactDetector::fillKeptSprings(ParticleStorage& ps, std::size_t first) {
    if (!m_carried.empty()) {
        if (first != 0)
            throw core::Error("contact detection: springs carried over a rebuild, but the fill "
                              "starts at pair " +
                              std::to_string(first));
        // Also when the new list keeps no pair: the springs no pair takes go back while m_pass
        // is still the pass that stamped them (a contact new since the fill has no entry).
        fillCarriedSprings(ps);
    } else if (m_list.numKept() != 0) {
        m_list.forEachKeptPair(
            [&](std::size_t i, std::size_t j, std::size_t p) {
                m_list.spring(p) = springFromHistory(ps, i, j, m_list.hint(p));
            },
            first);
    }
    m_springsLive = true;
}

KeptSpring ContactDetector::springFromHistory(ParticleStorage const& ps, std::size_t i,
                                              std::size_t j, std::uint8_t& hint) {
    ContactHistory const& history = ps.history(i);
    HistoryEntry const* e = history.find(ps.uid(j));
    if (e == nullptr)
        return KeptSpring{};
    // The slot, for writeBackSpring (a hint: verified there).
    hint = static_cast<std::uint8_t>(std::min<std::ptrdiff_t>(e - history.begin(), 255));
    return KeptSpring{e->spring, e->stamp};
}

void ContactDetector::writeBackSpring(ParticleStorage& ps, std::size_t i, Uid partner,
                                      KeptSpring const& kept, std::uint8_t hint) const {
    if (kept.stamp == KeptSpring::kUntouched)
        return; // filled from an absent entry, never touched since
    ContactHistory& history = ps.history(i);
    HistoryEntry const entry{partner, kept.spring, kept.stamp};
    if (HistoryEntry* e = history.find(entry.partner, hint))
        *e = entry;
    else if (kept.stamp == m_pass) // a contact of the last pass (new since the fill)
        history.set(entry);
}

void ContactDetector::writeBackSprings(ParticleStorage& ps) {
    writeBackCarried(ps);
    if (!m_springsLive)
        return;
    m_springsLive = false;
    if (m_list.numKept() == 0)
        return;
    // Kept pairs inside the block join two masters that cannot leave it while the springs are
    // live: both are alive.
    m_list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        writeBackSpring(ps, i, ps.uid(j), m_list.spring(p), m_list.hint(p));
    });
}

void ContactDetector::countKeptContacts(std::span<std::uint32_t> perCopy) const {
    if (!m_springsLive || m_list.numKept() == 0)
        return;
    m_list.forEachKeptPair([&](std::size_t i, std::size_t, std::size_t p) {
        if (m_list.spring(p).stamp != m_pass)
            return;
        if (i >= perCopy.size()) // the storage changed since the pass, which it may not
            throw core::Error("contact detection: a kept spring of copy " + std::to_string(i) +
                              " counted for a storage of " + std::to_string(perCopy.size()));
        ++perCopy[i];
    });
}

} // namespace regolith::particles
