#include "particles/storage/ContactHistory.hpp"

#include <algorithm>

namespace regolith::particles {

namespace {
bool byPartner(HistoryEntry const& e, Uid uid) {
    return e.partner < uid;
}
} // namespace

ContactHistory::ContactHistory(ContactHistory const& other)
    : m_entries(other.m_entries ? std::make_unique<std::vector<HistoryEntry>>(*other.m_entries)
                                : nullptr) {}

ContactHistory& ContactHistory::operator=(ContactHistory const& other) {
    if (this != &other)
        m_entries = other.m_entries ? std::make_unique<std::vector<HistoryEntry>>(*other.m_entries)
                                    : nullptr;
    return *this;
}

std::vector<HistoryEntry>& ContactHistory::ensure() {
    if (!m_entries)
        m_entries = std::make_unique<std::vector<HistoryEntry>>();
    return *m_entries;
}

HistoryEntry const* ContactHistory::find(Uid partner) const {
    auto const& v = entries();
    auto it = std::lower_bound(v.begin(), v.end(), partner, byPartner);
    return it != v.end() && it->partner == partner ? &*it : nullptr;
}

HistoryEntry* ContactHistory::find(Uid partner) {
    if (!m_entries)
        return nullptr;
    auto& v = *m_entries;
    auto it = std::lower_bound(v.begin(), v.end(), partner, byPartner);
    return it != v.end() && it->partner == partner ? &*it : nullptr;
}

HistoryEntry& ContactHistory::touch(Uid partner, std::uint32_t stamp) {
    bool again = false;
    return touchAt(partner, stamp, again);
}

HistoryEntry& ContactHistory::touchAt(Uid partner, std::uint32_t stamp, bool& again) {
    auto& v = ensure();
    auto it = std::lower_bound(v.begin(), v.end(), partner, byPartner);
    if (it == v.end() || it->partner != partner)
        it = v.insert(it, HistoryEntry{partner, core::Vec3::Zero(), stamp});
    else
        again = it->stamp == stamp;
    it->stamp = stamp;
    return *it;
}

HistoryEntry& ContactHistory::touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint,
                                        bool& again) {
    again = false;
    HistoryEntry& e = touchAt(partner, stamp, again);
    auto const slot = static_cast<std::size_t>(&e - m_entries->data());
    // Beyond 255 entries the hint saturates and always misses (then touch() searches).
    hint = static_cast<std::uint8_t>(std::min<std::size_t>(slot, 255));
    return e;
}

void ContactHistory::set(HistoryEntry const& entry) {
    auto& v = ensure();
    auto it = std::lower_bound(v.begin(), v.end(), entry.partner, byPartner);
    if (it != v.end() && it->partner == entry.partner)
        *it = entry;
    else
        v.insert(it, entry);
}

void ContactHistory::assign(std::vector<HistoryEntry> const& entries) {
    if (entries.empty())
        m_entries.reset();
    else
        ensure().assign(entries.begin(), entries.end());
}

bool ContactHistory::erase(Uid partner) {
    if (!m_entries)
        return false;
    auto& v = *m_entries;
    auto it = std::lower_bound(v.begin(), v.end(), partner, byPartner);
    if (it == v.end() || it->partner != partner)
        return false;
    v.erase(it);
    if (v.empty())
        m_entries.reset();
    return true;
}

std::size_t ContactHistory::keepOnlySlow(std::uint32_t stamp) {
    auto& v = *m_entries;
    auto const before = v.size();
    std::erase_if(v, [stamp](HistoryEntry const& e) { return e.stamp != stamp; });
    std::size_t const dropped = before - v.size();
    if (v.empty())
        m_entries.reset(); // a particle that lost all contacts gives its memory back
    return dropped;
}

} // namespace regolith::particles
