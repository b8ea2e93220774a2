#include "particles/storage/CopyIndex.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace regolith::particles {

std::size_t CopyIndex::probe(CopyKey const& key) const {
    std::size_t const mask = m_slots.size() - 1;
    for (std::size_t s = home(key);; s = (s + 1) & mask) {
        Slot const& slot = m_slots[s];
        if (slot.uid == kInvalidUid || (slot.uid == key.uid && slot.image == key.image))
            return s;
    }
}

std::uint32_t CopyIndex::find(CopyKey const& key) const {
    if (m_size == 0)
        return kNone;
    Slot const& slot = m_slots[probe(key)];
    return slot.uid == kInvalidUid ? kNone : slot.index;
}

bool CopyIndex::insert(CopyKey const& key, std::uint32_t index) {
    if (4 * (m_size + 1) > 3 * m_slots.size())
        grow(m_size + 1);
    Slot& slot = m_slots[probe(key)];
    if (slot.uid != kInvalidUid)
        return false;
    slot = Slot{key.uid, key.image, index};
    ++m_size;
    return true;
}

void CopyIndex::assign(CopyKey const& key, std::uint32_t index) {
    if (!insert(key, index))
        m_slots[probe(key)].index = index;
}

void CopyIndex::erase(CopyKey const& key) {
    if (m_size == 0)
        return;
    std::size_t const mask = m_slots.size() - 1;
    std::size_t hole = probe(key);
    if (m_slots[hole].uid == kInvalidUid)
        return;
    // Backward shift: move every later entry of the run whose home is not cyclically in
    // (hole, s] into the hole, so that probing never needs tombstones.
    for (std::size_t s = (hole + 1) & mask; m_slots[s].uid != kInvalidUid; s = (s + 1) & mask) {
        std::size_t const h = home(CopyKey{m_slots[s].uid, m_slots[s].image});
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
    std::vector<Slot> old = std::exchange(m_slots, std::vector<Slot>(slots));
    m_shift = 64U - static_cast<unsigned>(std::countr_zero(slots));
    for (Slot const& s : old)
        if (s.uid != kInvalidUid)
            m_slots[probe(CopyKey{s.uid, s.image})] = s;
}

} // namespace regolith::particles
