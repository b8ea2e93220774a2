#include "particles/storage/ContactHistory.hpp"

#include <algorithm>

namespace regolith::particles {

namespace {
bool byPartner(HistoryEntry const& e, Uid uid) {
    return e.partner < uid;
}
} // namespace

HistoryEntry const* ContactHistory::find(Uid partner) const {
    auto it = std::lower_bound(m_entries.begin(), m_entries.end(), partner, byPartner);
    return it != m_entries.end() && it->partner == partner ? &*it : nullptr;
}

HistoryEntry* ContactHistory::find(Uid partner) {
    auto it = std::lower_bound(m_entries.begin(), m_entries.end(), partner, byPartner);
    return it != m_entries.end() && it->partner == partner ? &*it : nullptr;
}

HistoryEntry& ContactHistory::touch(Uid partner, std::uint32_t stamp) {
    auto it = std::lower_bound(m_entries.begin(), m_entries.end(), partner, byPartner);
    if (it == m_entries.end() || it->partner != partner)
        it = m_entries.insert(it, HistoryEntry{partner, core::Vec3::Zero(), stamp});
    it->stamp = stamp;
    return *it;
}

HistoryEntry& ContactHistory::touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint) {
    HistoryEntry& e = touch(partner, stamp);
    auto const slot = static_cast<std::size_t>(&e - m_entries.data());
    // Beyond 255 entries the hint saturates and always misses (then touch() searches).
    hint = static_cast<std::uint8_t>(std::min<std::size_t>(slot, 255));
    return e;
}

void ContactHistory::set(HistoryEntry const& entry) {
    auto it = std::lower_bound(m_entries.begin(), m_entries.end(), entry.partner, byPartner);
    if (it != m_entries.end() && it->partner == entry.partner)
        *it = entry;
    else
        m_entries.insert(it, entry);
}

bool ContactHistory::erase(Uid partner) {
    auto it = std::lower_bound(m_entries.begin(), m_entries.end(), partner, byPartner);
    if (it == m_entries.end() || it->partner != partner)
        return false;
    m_entries.erase(it);
    return true;
}

std::size_t ContactHistory::keepOnlySlow(std::uint32_t stamp) {
    auto const before = m_entries.size();
    std::erase_if(m_entries, [stamp](HistoryEntry const& e) { return e.stamp != stamp; });
    if (m_entries.empty())
        m_entries.shrink_to_fit(); // a particle that lost all contacts gives its memory back
    return before - m_entries.size();
}

} // namespace regolith::particles
