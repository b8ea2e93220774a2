#include "particles/detection/VerletList.hpp"

#include "core/Error.hpp"
#include "core/memory/GentleGrowth.hpp"

#include <cmath>

namespace regolith::particles {

void VerletList::restart(ParticleStorage& ps, double skin) {
    if (ps.size() >= kDead)
        throw core::Error("VerletList: too many copies for 32-bit ids");
    m_session = ps.startTracing();
    m_storage = &ps;
    m_skin = skin;
    m_built = ps.size();
    m_pairs.clear();
    m_owned = 0;
    m_mode.clear();
    m_hint.clear();
    m_arrivals.clear();
    // Room for the copies that arrive before the next rebuild (follow), so that the first
    // arrival does not reallocate these per-copy arrays: a reallocation holds the old and
    // the new array at once, 28 more bytes per copy at that moment (the run's peak).
    m_indexOf.reserve(core::gentleCapacity(m_built));
    m_reference.reserve(core::gentleCapacity(m_built));
    m_indexOf.resize(m_built);
    for (std::size_t k = 0; k < m_built; ++k)
        m_indexOf[k] = static_cast<std::uint32_t>(k);
    m_reference.assign(ps.positions().begin(), ps.positions().end());
}

bool VerletList::follow(ParticleStorage& ps, std::vector<std::size_t>& fresh) {
    fresh.clear();
    if (m_storage != &ps || ps.traceSession() != m_session || ps.traceBroken())
        return false;
    auto const journal = ps.traceJournal();
    // The ids of every written slot die ... unless they turn up in another written slot.
    for (TraceChange const& c : journal)
        if (c.previous != ParticleStorage::kUntraced)
            m_indexOf[c.previous] = kDead;
    std::size_t const n = ps.size();
    for (TraceChange const& c : journal) {
        if (c.index >= n)
            continue; // dropped from the end
        Id id = ps.traceTag(c.index);
        if (id == ParticleStorage::kUntraced) {
            if (m_indexOf.size() >= kDead)
                return false; // out of ids: rebuild
            id = static_cast<Id>(m_indexOf.size());
            ps.setTraceTag(c.index, id);
            core::reserveForAppend(m_indexOf); // per-copy arrays sized at restart: no doubling
            core::reserveForAppend(m_reference);
            m_indexOf.push_back(kDead);
            m_reference.push_back(ps.position(c.index));
            m_arrivals.push_back(id);
            fresh.push_back(c.index);
        }
        m_indexOf[id] = c.index;
    }
    ps.clearTraceJournal();
    return true;
}

bool VerletList::movedTooFar(ParticleStorage const& ps) const {
    double const half = 0.5 * m_skin;
    double const limit = half * half;
    auto const& x = ps.positions();
    bool far = false; // no early exit: the loop stays branch-free
    for (std::size_t k = 0, n = ps.size(); k < n; ++k) {
        core::Vec3 const d = x[k] - m_reference[ps.traceTag(k)];
        far |= !(d.squaredNorm() < limit); // NaN too
    }
    return far;
}

std::size_t VerletList::bytes() const {
    return m_pairs.capacity() * sizeof(m_pairs[0]) + m_mode.capacity() + m_hint.capacity() +
           m_indexOf.capacity() * sizeof(std::uint32_t) +
           m_reference.capacity() * sizeof(core::Vec3) + m_arrivals.capacity() * sizeof(Id);
}

} // namespace regolith::particles
