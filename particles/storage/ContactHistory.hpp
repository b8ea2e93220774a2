#pragma once
/// The tangential-spring history of one particle's contacts, keyed by partner uid, kept with
/// the particle so that it travels with it (DESIGN.md: whichever block evaluates a contact
/// finds its history). A pair's entry lives on the partner with the smaller uid (the `i` of
/// the canonical contact order); a sphere–wall entry lives on the sphere, keyed by the wall's
/// uid.
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"

#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

namespace regolith::particles {

/// One contact's memory.
struct HistoryEntry {
    Uid partner = kInvalidUid;
    /// Accumulated tangential displacement of the partner relative to the owner at the
    /// contact point, kept in the current tangent plane [length].
    core::Vec3 spring = core::Vec3::Zero();
    /// The evaluation pass that last touched this entry (see `keepOnly`).
    std::uint32_t stamp = 0;
};

/// A small array of `HistoryEntry` sorted by partner uid: look-up is a binary search over a
/// handful of entries, iteration order is canonical (by uid), and an empty history costs no
/// heap memory.
///
/// Memory and access: every copy of every grain has one, and most (a sparse gas: nearly all)
/// are empty, so it is a single pointer (8 bytes), null while empty, to ONE heap block that
/// holds the entry count, the capacity and the entries. The contact loop touches a history per
/// contact, at scattered addresses: one block is one dependent load fewer than a pointer to a
/// std::vector (the vector object, then its buffer); the dense ramp's contact phase ran 1.08x
/// faster with it (docs/results.md).
class ContactHistory {
public:
    ContactHistory() = default;
    ContactHistory(ContactHistory const& other);
    ContactHistory& operator=(ContactHistory const& other);
    ContactHistory(ContactHistory&& other) noexcept
        : m_block(std::exchange(other.m_block, nullptr)) {}
    ContactHistory& operator=(ContactHistory&& other) noexcept {
        if (this != &other) {
            release();
            m_block = std::exchange(other.m_block, nullptr);
        }
        return *this;
    }
    ~ContactHistory() { release(); }

    /// The entry for `partner`, or nullptr.
    [[nodiscard]] HistoryEntry const* find(Uid partner) const;
    [[nodiscard]] HistoryEntry* find(Uid partner);
    /// The entry for `partner` (created with a zero spring if absent), stamped with `stamp`.
    HistoryEntry& touch(Uid partner, std::uint32_t stamp);
    /// touch() that first tries slot `hint` (where the entry sat last time, e.g. kept by a
    /// neighbour list beside the pair) and updates it: no search while the partners of this
    /// particle stay the same. A wrong hint only costs the search.
    HistoryEntry& touch(Uid partner, std::uint32_t stamp, std::uint8_t& hint) {
        bool again = false;
        return touch(partner, stamp, hint, again);
    }
    /// touch() with a hint that also tells whether the entry had been stamped `stamp` already
    /// (`again`): touched earlier in the same pass, e.g. a pair that meets through two periodic
    /// images, whose second evaluation must see the spring the first one left.
    HistoryEntry& touch(Uid partner, std::uint32_t stamp, std::uint8_t& hint, bool& again) {
        if (m_block && hint < m_block->size && m_block->data()[hint].partner == partner)
            [[likely]] {
            HistoryEntry& e = m_block->data()[hint];
            again = e.stamp == stamp;
            e.stamp = stamp;
            return e;
        }
        return touchSlow(partner, stamp, hint, again);
    }
    /// Starts loading the block into the cache (the per-step prune calls it a few grains
    /// ahead).
    [[gnu::always_inline]] void prefetch() const { __builtin_prefetch(m_block); }
    /// Inserts or overwrites an entry (used when history arrives with a particle).
    void set(HistoryEntry const& entry);
    /// Replaces every entry by `entries` (sorted by partner uid, unique: another history's
    /// entries), reusing the heap block if it is large enough: a shadow takes its master's
    /// history every step.
    void assign(std::span<HistoryEntry const> entries);
    /// Removes the entry for `partner`; returns whether there was one.
    bool erase(Uid partner);
    /// Drops every entry whose stamp differs from `stamp`: the contacts not evaluated in the
    /// current pass are broken. Returns how many were dropped.
    std::size_t keepOnly(std::uint32_t stamp) {
        return m_block ? keepOnlySlow(stamp) : 0; // most grains: no contact
    }

    [[nodiscard]] std::size_t size() const { return m_block ? m_block->size : 0; }
    [[nodiscard]] bool empty() const { return !m_block; }
    void clear() { release(); }
    [[nodiscard]] HistoryEntry const* begin() const { return entries().data(); }
    [[nodiscard]] HistoryEntry const* end() const { return begin() + size(); }
    /// Heap bytes held (capacity, not size).
    [[nodiscard]] std::size_t heapBytes() const {
        return m_block ? Block::bytes(m_block->capacity) : 0;
    }
    /// The entries in uid order (for packing into messages).
    [[nodiscard]] std::span<HistoryEntry const> entries() const {
        return m_block ? std::span<HistoryEntry const>(m_block->data(), m_block->size)
                       : std::span<HistoryEntry const>{};
    }

private:
    /// The heap block: this header, then `capacity` entries (all constructed; the first `size`
    /// in use). HistoryEntry is trivially destructible, so freeing is just deallocation.
    struct Block {
        std::uint32_t size = 0;
        std::uint32_t capacity = 0;

        [[nodiscard]] HistoryEntry* data() {
            return std::launder(reinterpret_cast<HistoryEntry*>(this + 1));
        }
        [[nodiscard]] HistoryEntry const* data() const {
            return std::launder(reinterpret_cast<HistoryEntry const*>(this + 1));
        }
        static constexpr std::size_t bytes(std::size_t capacity) {
            return sizeof(Block) + capacity * sizeof(HistoryEntry);
        }
    };
    static_assert(sizeof(Block) % alignof(HistoryEntry) == 0);
    static_assert(std::is_trivially_destructible_v<HistoryEntry>);

    std::size_t keepOnlySlow(std::uint32_t stamp);
    /// touch() by search; `again` as in the hinted touch (left alone for a new entry).
    HistoryEntry& touchAt(Uid partner, std::uint32_t stamp, bool& again);
    HistoryEntry& touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint, bool& again);
    /// Where `partner` is or would go: the first entry not below it.
    [[nodiscard]] std::size_t lowerBound(Uid partner) const;
    /// Inserts `entry` at slot `at`, growing the block (or creating it) if full.
    HistoryEntry& insertAt(std::size_t at, HistoryEntry const& entry);
    /// A block of `capacity` default entries holding the first `keep` entries of the current
    /// one (if any), replacing it.
    void reallocate(std::size_t capacity, std::size_t keep);
    void release();

    /// Null when empty (invariant: never points to a block with no entries).
    Block* m_block = nullptr;
};

} // namespace regolith::particles
