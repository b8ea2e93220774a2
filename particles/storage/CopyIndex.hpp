#pragma once
/// The (uid, image) -> storage index map of ParticleStorage: an open-addressing hash table
/// with linear probing and backward-shift deletion (Knuth, TAOCP vol. 3, sec. 6.4, Algorithm
/// R), in one flat array of 8-byte slots. Why not std::unordered_map: one heap node per copy
/// (~56 bytes with its bucket) and a pointer chase per look-up, on the synchronisation's hot
/// path (every shadow update looks its copy up).
///
/// Memory: a slot holds the index and 32 bits of the key's hash, not the key: the key is
/// already stored by the owner (ParticleStorage's uid and image arrays), which every call
/// passes as `keyAt` (index -> CopyKey). A hash match is confirmed there, so equal hash bits
/// of two keys cost one more comparison, never a wrong answer. At most 3/4 full, the slot
/// array sized to the keys (the home slot is the hash scaled to the table, Lemire's
/// multiply-shift, not masked bits of it, so any size works): ~11 bytes per key, where a
/// power-of-two table held 11-21 (16.7 for the sparse gas's 2 M copies per rank).
///
/// Contract for `keyAt`: for every index stored in the table, keyAt(index) returns the key
/// it was stored under (the owner keeps its arrays and the table in step).
#include "particles/storage/CopyImage.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace regolith::particles {

class CopyIndex {
public:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

    /// The index stored for `key`, or kNone.
    template <class KeyAt>
    [[nodiscard]] std::uint32_t find(CopyKey const& key, KeyAt const& keyAt) const {
        if (m_size == 0)
            return kNone;
        return m_slots[probe(key, keyAt)].index;
    }
    /// Starts loading the slot where a look-up of `key` begins: a caller that knows its next
    /// keys a few iterations ahead hides the cache miss that a look-up in a large table is.
    /// Always inlined: GCC 12 deems a function whose only effect is a prefetch pure, and drops
    /// calls to it (prefetch and all) unless the prefetch is inlined first. An empty table has
    /// no slots: the address is then data() + 0.
    [[gnu::always_inline]] void prefetch(CopyKey const& key) const {
        __builtin_prefetch(m_slots.data() + homeOfTag(tagOf(key)));
    }
    /// Stores key -> index unless the key is present; returns whether it inserted. `index`
    /// need not be valid for keyAt yet (ParticleStorage inserts before it appends).
    template <class KeyAt>
    bool insert(CopyKey const& key, std::uint32_t index, KeyAt const& keyAt) {
        if (4 * (m_size + 1) > 3 * m_slots.size())
            grow(m_size + 1);
        Slot& slot = m_slots[probe(key, keyAt)];
        if (slot.index != kNone)
            return false;
        slot = Slot{index, tagOf(key)};
        ++m_size;
        return true;
    }
    /// Stores key -> index, replacing any index the key had.
    template <class KeyAt>
    void assign(CopyKey const& key, std::uint32_t index, KeyAt const& keyAt) {
        if (4 * (m_size + 1) > 3 * m_slots.size())
            grow(m_size + 1);
        Slot& slot = m_slots[probe(key, keyAt)];
        if (slot.index == kNone) {
            slot.tag = tagOf(key);
            ++m_size;
        }
        slot.index = index;
    }
    /// Removes the key (no-op if absent).
    template <class KeyAt>
    void erase(CopyKey const& key, KeyAt const& keyAt) {
        if (m_size != 0)
            eraseSlot(probe(key, keyAt));
    }
    /// Room for `n` keys without growing.
    void reserve(std::size_t n);
    void clear();
    [[nodiscard]] std::size_t size() const { return m_size; }
    /// Heap bytes held.
    [[nodiscard]] std::size_t bytes() const { return m_slots.capacity() * sizeof(Slot); }

private:
    struct Slot {
        std::uint32_t index = kNone; ///< kNone: empty
        std::uint32_t tag = 0;       ///< the top 32 bits of the key's mixed hash
    };
    /// The key's hash, mixed so that its top bits are good: the tag is its top 32 bits, the
    /// home slot tag * slots / 2^32 (so the table can be rehashed and shifted without the
    /// keys, and homes are in tag order).
    [[nodiscard]] static std::uint64_t mixed(CopyKey const& key) {
        return CopyKeyHash{}(key)*0x9E3779B97F4A7C15ULL;
    }
    [[nodiscard]] static std::uint32_t tagOf(CopyKey const& key) {
        return static_cast<std::uint32_t>(mixed(key) >> 32U);
    }
    [[nodiscard]] std::size_t homeOfTag(std::uint32_t tag) const {
        return static_cast<std::size_t>((std::uint64_t{tag} * m_slots.size()) >> 32U);
    }
    [[nodiscard]] std::size_t next(std::size_t s) const {
        return s + 1 == m_slots.size() ? 0 : s + 1;
    }
    /// The slot holding `key`, or the empty slot where it would go.
    template <class KeyAt>
    [[nodiscard]] std::size_t probe(CopyKey const& key, KeyAt const& keyAt) const {
        std::uint32_t const tag = tagOf(key);
        for (std::size_t s = homeOfTag(tag);; s = next(s)) {
            Slot const& slot = m_slots[s];
            if (slot.index == kNone || (slot.tag == tag && keyAt(slot.index) == key))
                return s;
        }
    }
    void eraseSlot(std::size_t hole);
    void grow(std::size_t minKeys);

    std::vector<Slot> m_slots; ///< at most 2^32 slots, at most 3/4 full
    std::size_t m_size = 0;
};

} // namespace regolith::particles
