#pragma once
/// The (uid, image) -> storage index map of ParticleStorage: an open-addressing hash table
/// with linear probing and backward-shift deletion (Knuth, TAOCP vol. 3, sec. 6.4, Algorithm
/// R), in one flat array of 16-byte slots. Why not std::unordered_map: one heap node per copy
/// (~56 bytes with its bucket) and a pointer chase per look-up, on the synchronisation's hot
/// path (every shadow update looks its copy up).
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
    [[nodiscard]] std::uint32_t find(CopyKey const& key) const;
    /// Stores key -> index unless the key is present; returns whether it inserted.
    bool insert(CopyKey const& key, std::uint32_t index);
    /// Stores key -> index, replacing any index the key had.
    void assign(CopyKey const& key, std::uint32_t index);
    /// Removes the key (no-op if absent).
    void erase(CopyKey const& key);
    /// Room for `n` keys without growing.
    void reserve(std::size_t n);
    void clear();
    [[nodiscard]] std::size_t size() const { return m_size; }
    /// Heap bytes held.
    [[nodiscard]] std::size_t bytes() const { return m_slots.capacity() * sizeof(Slot); }

private:
    struct Slot {
        Uid uid = kInvalidUid; ///< kInvalidUid: empty
        CopyImage image = kNoImage;
        std::uint32_t index = kNone;
    };
    [[nodiscard]] std::size_t home(CopyKey const& key) const {
        return CopyKeyHash{}(key)*0x9E3779B97F4A7C15ULL >> m_shift;
    }
    /// The slot holding `key`, or the empty slot where it would go.
    [[nodiscard]] std::size_t probe(CopyKey const& key) const;
    void grow(std::size_t minSlots);

    std::vector<Slot> m_slots; ///< power-of-two size, at most 3/4 full
    std::size_t m_size = 0;
    unsigned m_shift = 64; ///< 64 - log2(slots)
};

} // namespace regolith::particles
