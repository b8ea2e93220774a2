#include "particles/storage/ContactHistory.hpp"

#include <algorithm>
#include <utility>

namespace regolith::particles {

namespace {
bool byPartner(HistoryEntry const& e, Uid uid) {
    return e.partner < uid;
}
} // namespace

std::size_t ContactHistory::lowerBound(Uid partner) const {
    return static_cast<std::size_t>(std::lower_bound(begin(), end(), partner, byPartner) - begin());
}

HistoryEntry const* ContactHistory::find(Uid partner) const {
    std::size_t const at = lowerBound(partner);
    return at < size() && m_entries[at].partner == partner ? &m_entries[at] : nullptr;
}

HistoryEntry* ContactHistory::find(Uid partner) {
    return const_cast<HistoryEntry*>(std::as_const(*this).find(partner));
}

HistoryEntry& ContactHistory::touch(Uid partner, std::uint32_t stamp) {
    bool again = false;
    return touchAt(partner, stamp, again);
}

HistoryEntry& ContactHistory::touchAt(Uid partner, std::uint32_t stamp, bool& again) {
    std::size_t const at = lowerBound(partner);
    if (at == size() || m_entries[at].partner != partner)
        return *m_entries.insert(begin() + at, HistoryEntry{partner, core::Vec3::Zero(), stamp});
    HistoryEntry& e = m_entries[at];
    renew(e, stamp, again);
    return e;
}

HistoryEntry& ContactHistory::touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint,
                                        bool& again) {
    again = false;
    HistoryEntry& e = touchAt(partner, stamp, again);
    auto const slot = static_cast<std::size_t>(&e - begin());
    // Beyond 255 entries the hint saturates and always misses (then touch() searches).
    hint = static_cast<std::uint8_t>(std::min<std::size_t>(slot, 255));
    return e;
}

void ContactHistory::set(HistoryEntry const& entry) {
    std::size_t const at = lowerBound(entry.partner);
    if (at < size() && m_entries[at].partner == entry.partner)
        m_entries[at] = entry;
    else
        m_entries.insert(begin() + at, entry);
}

bool ContactHistory::erase(Uid partner) {
    std::size_t const at = lowerBound(partner);
    if (at == size() || m_entries[at].partner != partner)
        return false;
    m_entries.erase(begin() + at, begin() + at + 1); // the last entry: the block goes too
    return true;
}

std::size_t ContactHistory::keepOnlySlow(std::uint32_t stamp) {
    std::size_t const before = size();
    HistoryEntry* kept =
        std::remove_if(m_entries.begin(), m_entries.end(),
                       [stamp](HistoryEntry const& e) { return e.stamp != stamp; });
    // A particle that lost all contacts gives its memory back (erasing every entry frees it).
    m_entries.erase(kept, end());
    return before - size();
}

} // namespace regolith::particles
