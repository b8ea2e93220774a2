/// The kept springs carried over a rebuild (SpringCarry.hpp), and ContactDetector's use of them:
/// the histories serve only the pairs the last list did not keep, and take back what the new one
/// does not keep; before a synchronisation, those of the pairs it takes a copy from.
#include "particles/detection/SpringCarry.hpp"

#include "particles/detection/ContactDetector.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

void CarriedSprings::setAside(VerletList const& list, std::size_t copies) {
    m_springs.clear();
    if (list.numKept() == 0)
        return;
    auto const touched = [&](std::size_t p) {
        return list.spring(p).stamp != KeptSpring::kUntouched;
    };
    // A counting sort by i: counts shifted by one, then their prefix sums.
    m_start.assign(copies + 1, 0);
    list.forEachKeptPair(
        [&](std::size_t i, std::size_t, std::size_t p) { m_start[i + 1] += touched(p) ? 1 : 0; });
    for (std::size_t k = 1; k < m_start.size(); ++k)
        m_start[k] += m_start[k - 1];
    // With room for a quarter more: a pack's count creeps up from rebuild to rebuild, and each
    // growth would move the springs to memory touched for the first time.
    if (m_springs.capacity() < m_start.back())
        m_springs.reserve(m_start.back() + m_start.back() / 4);
    m_springs.resize(m_start.back());
    m_cursor.assign(m_start.begin(), m_start.end() - 1);
    list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (touched(p))
            m_springs[m_cursor[i]++] =
                Spring{static_cast<std::uint32_t>(j), list.hint(p), list.spring(p)};
    });
}

CarriedSprings::Spring const* CarriedSprings::take(std::size_t i, std::size_t j) {
    Spring* c = m_springs.data() + m_start[i];
    Spring* const last = m_springs.data() + m_start[i + 1];
    while (c != last && c->partner != j)
        ++c;
    if (c == last)
        return nullptr;
    Spring const* const taken = c;
    c->partner = kTaken; // its value stays for the caller
    return taken;
}

std::size_t CarriedSprings::bytes() const {
    return m_springs.capacity() * sizeof(Spring) +
           (m_start.capacity() + m_cursor.capacity()) * sizeof(std::uint32_t);
}

void ContactDetector::carrySprings(ParticleStorage const& ps) {
    m_springsLive = false;
    m_carried.setAside(m_list, ps.size());
}

void ContactDetector::fillCarriedSprings(ParticleStorage& ps) {
    // The list was rebuilt on the storage the springs were carried from: ids are indices.
    m_list.forEachKeptPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (CarriedSprings::Spring const* c = m_carried.take(i, j)) {
            m_list.spring(p) = c->spring;
            m_list.hint(p) = c->hint;
        } else {
            m_list.spring(p) = springFromHistory(ps, i, j, m_list.hint(p));
        }
    });
    writeBackCarried(ps); // those the new list does not keep
}

void ContactDetector::writeBackCarried(ParticleStorage& ps) {
    m_carried.drain([&](std::size_t i, CarriedSprings::Spring const& c) {
        writeBackSpring(ps, i, ps.uid(c.partner), c.spring, c.hint);
    });
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
