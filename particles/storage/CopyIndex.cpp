#include "particles/storage/CopyIndex.hpp"

#include "core/Error.hpp"
#include "core/memory/GentleGrowth.hpp"

#include <algorithm>
#include <utility>

namespace regolith::particles {

void CopyIndex::eraseSlot(std::size_t hole) {
    if (m_slots[hole].index == kNone)
        return;
    // Backward shift: move every later entry of the run whose home is not cyclically in
    // (hole, s] into the hole, so that probing never needs tombstones. The home comes from the
    // tag: no key is needed.
    for (std::size_t s = next(hole); m_slots[s].index != kNone; s = next(s)) {
        std::size_t const h = homeOfTag(m_slots[s].tag);
        bool const stays = hole <= s ? (hole < h && h <= s) : (hole < h || h <= s);
        if (!stays) {
            m_slots[hole] = m_slots[s];
            hole = s;
        }
    }
    m_slots[hole] = Slot{};
    --m_size;
}

void CopyIndex::reserve(std::size_t n) {
    if (4 * n > 3 * m_slots.size())
        grow(core::gentleCapacity(n)); // room for a few more (a storage's first shadows)
}

void CopyIndex::clear() {
    m_slots.clear();
    m_slots.shrink_to_fit();
    m_size = 0;
}

void CopyIndex::grow(std::size_t minKeys) {
    // Growing by a sixteenth, not doubling (core/memory/GentleGrowth.hpp): rehashes stay
    // amortised O(1) per key, and old and new table side by side cost ~23 bytes per key,
    // not ~32.
    std::size_t slots = std::max<std::size_t>(16, (4 * minKeys + 2) / 3);
    slots = std::max(slots, core::gentleCapacity(m_slots.size()));
    if (slots > (std::size_t{1} << 32U)) // a home is tag * slots / 2^32
        throw core::Error("CopyIndex: more than 2^32 slots");
    std::vector<Slot> old = std::exchange(m_slots, std::vector<Slot>(slots));
    // Keys are distinct, so a rehash only needs the first empty slot from each home.
    for (Slot const& s : old)
        if (s.index != kNone) {
            std::size_t at = homeOfTag(s.tag);
            while (m_slots[at].index != kNone)
                at = next(at);
            m_slots[at] = s;
        }
}

} // namespace regolith::particles
