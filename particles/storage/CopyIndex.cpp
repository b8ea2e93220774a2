#include "particles/storage/CopyIndex.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace regolith::particles {

void CopyIndex::eraseSlot(std::size_t hole) {
    if (m_slots[hole].index == kNone)
        return;
    std::size_t const mask = m_slots.size() - 1;
    // Backward shift: move every later entry of the run whose home is not cyclically in
    // (hole, s] into the hole, so that probing never needs tombstones. The home comes from the
    // tag: no key is needed.
    for (std::size_t s = (hole + 1) & mask; m_slots[s].index != kNone; s = (s + 1) & mask) {
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
        grow(n);
}

void CopyIndex::clear() {
    m_slots.clear();
    m_slots.shrink_to_fit();
    m_size = 0;
    m_shift = 64;
}

void CopyIndex::grow(std::size_t minKeys) {
    std::size_t slots = std::bit_ceil(std::max<std::size_t>(16, (4 * minKeys + 2) / 3));
    if (slots <= m_slots.size())
        slots = 2 * m_slots.size();
    if (slots > (std::size_t{1} << 32U)) // the home must fit the 32 tag bits
        throw core::Error("CopyIndex: more than 2^32 slots");
    std::vector<Slot> old = std::exchange(m_slots, std::vector<Slot>(slots));
    m_shift = 64U - static_cast<unsigned>(std::countr_zero(slots));
    std::size_t const mask = slots - 1;
    // Keys are distinct, so a rehash only needs the first empty slot from each home.
    for (Slot const& s : old)
        if (s.index != kNone) {
            std::size_t at = homeOfTag(s.tag);
            while (m_slots[at].index != kNone)
                at = (at + 1) & mask;
            m_slots[at] = s;
        }
}

} // namespace regolith::particles
