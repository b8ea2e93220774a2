/// The kept springs carried from one Verlet list to the next (ContactDetector's class comment,
/// "Springs kept beside the list"): at a rebuild the live springs are set aside by the storage
/// index of their pair's canonical i (a counting sort) instead of going back to the grains'
/// histories, and each kept pair of the new list takes its partner's from i's run. The
/// histories serve only the pairs the last list did not keep, and take back what the new one
/// does not keep; before a synchronisation, those of the pairs it takes a copy from.
#include "particles/detection/ContactDetector.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

namespace {

/// A carried spring's partner once a new pair took it.
constexpr std::uint32_t kTaken = 0xffffffffu;

/// Turns counts shifted by one (count of k in start[k + 1]) into a counting sort's offsets.
void prefixSums(std::vector<std::uint32_t>& start) {
    for (std::size_t k = 1; k < start.size(); ++k)
        start[k] += start[k - 1];
}

} // namespace

void ContactDetector::carrySprings(ParticleStorage const& ps) {
    m_springsLive = false;
    m_carried.clear();
    if (m_list.numKept() == 0)
        return;
    // A spring filled from an absent entry and never touched since would not be written back
    // (writeBackSpring): the fill finds the same absent entry.
    auto const touched = [&](std::size_t p) {
        return m_list.spring(p).stamp != KeptSpring::kUntouched;
    };
    m_carriedStart.assign(ps.size() + 1, 0);
    m_list.forEachKeptPair([&](std::size_t i, std::size_t, std::size_t p) {
        m_carriedStart[i + 1] += touched(p) ? 1 : 0;
    });
    prefixSums(m_carriedStart);
    m_carried.resize(m_carriedStart.back());
    m_carryCursor.assign(m_carriedStart.begin(), m_carriedStart.end() - 1);
    m_list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (touched(p))
            m_carried[m_carryCursor[i]++] =
                CarriedSpring{static_cast<std::uint32_t>(j), m_list.hint(p), m_list.spring(p)};
    });
}

void ContactDetector::fillCarriedSprings(ParticleStorage& ps) {
    // The list was rebuilt on the storage the springs were carried from: ids are indices.
    m_list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        CarriedSpring* c = m_carried.data() + m_carriedStart[i];
        CarriedSpring* const last = m_carried.data() + m_carriedStart[i + 1];
        while (c != last && c->partner != j)
            ++c;
        if (c != last) {
            m_list.spring(p) = c->spring;
            m_list.hint(p) = c->hint;
            c->partner = kTaken;
        } else {
            m_list.spring(p) = springFromHistory(ps, i, j, m_list.hint(p));
        }
    });
    writeBackCarried(ps); // those the new list does not keep
}

void ContactDetector::writeBackCarried(ParticleStorage& ps) {
    if (m_carried.empty())
        return;
    for (std::size_t i = 0; i + 1 < m_carriedStart.size(); ++i)
        for (std::uint32_t k = m_carriedStart[i]; k < m_carriedStart[i + 1]; ++k) {
            CarriedSpring const& c = m_carried[k];
            if (c.partner != kTaken)
                writeBackSpring(ps, i, ps.uid(c.partner), c.spring, c.hint);
        }
    m_carried.clear();
}

void ContactDetector::writeBackLeaving(ParticleStorage& ps) {
    if (!m_springsLive || m_list.numKept() == 0)
        return;
    // The synchronisation moves the masters outside the block's box (ParticleSync's
    // ownership rule), the region the list was settled for: a pair with such a copy loses
    // it, and its spring lives on in the history (the copy's, if it is the canonical i).
    core::AABB const& box = m_listRegion;
    m_list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (!(box.contains(ps.position(i)) && box.contains(ps.position(j))))
            writeBackSpring(ps, i, ps.uid(j), m_list.spring(p), m_list.hint(p));
    });
}

} // namespace regolith::particles
