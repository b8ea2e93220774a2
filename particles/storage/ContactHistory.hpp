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
#include <memory>
#include <vector>

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

/// A small vector of `HistoryEntry` sorted by partner uid: look-up is a binary search over a
/// handful of entries, iteration order is canonical (by uid), and an empty history costs no
/// heap memory.
///
/// Memory: every copy of every grain has one, and most (a sparse gas: nearly all) are empty,
/// so it is a single pointer (8 bytes) to a vector that exists only while there are entries,
/// instead of an inline std::vector (24 bytes).
class ContactHistory {
public:
    ContactHistory() = default;
    ContactHistory(ContactHistory const& other);
    ContactHistory& operator=(ContactHistory const& other);
    ContactHistory(ContactHistory&&) noexcept = default;
    ContactHistory& operator=(ContactHistory&&) noexcept = default;
    ~ContactHistory() = default;

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
        if (m_entries && hint < m_entries->size() && (*m_entries)[hint].partner == partner)
            [[likely]] {
            auto& e = (*m_entries)[hint];
            again = e.stamp == stamp;
            e.stamp = stamp;
            return e;
        }
        return touchSlow(partner, stamp, hint, again);
    }
    /// Inserts or overwrites an entry (used when history arrives with a particle).
    void set(HistoryEntry const& entry);
    /// Replaces every entry by `entries` (sorted by partner uid, unique: another history's
    /// entries), reusing the heap block: a shadow takes its master's history every step.
    void assign(std::vector<HistoryEntry> const& entries);
    /// Removes the entry for `partner`; returns whether there was one.
    bool erase(Uid partner);
    /// Drops every entry whose stamp differs from `stamp`: the contacts not evaluated in the
    /// current pass are broken. Returns how many were dropped.
    std::size_t keepOnly(std::uint32_t stamp) {
        return m_entries ? keepOnlySlow(stamp) : 0; // most grains: no contact
    }

    [[nodiscard]] std::size_t size() const { return m_entries ? m_entries->size() : 0; }
    [[nodiscard]] bool empty() const { return !m_entries; }
    void clear() { m_entries.reset(); }
    [[nodiscard]] auto begin() const { return entries().begin(); }
    [[nodiscard]] auto end() const { return entries().end(); }
    /// Heap bytes held (capacity, not size).
    [[nodiscard]] std::size_t heapBytes() const {
        return m_entries ? sizeof(*m_entries) + m_entries->capacity() * sizeof(HistoryEntry) : 0;
    }
    /// The entries in uid order (for packing into messages).
    [[nodiscard]] std::vector<HistoryEntry> const& entries() const {
        return m_entries ? *m_entries : kNoEntries;
    }

private:
    std::size_t keepOnlySlow(std::uint32_t stamp);
    /// touch() by search; `again` as in the hinted touch (left alone for a new entry).
    HistoryEntry& touchAt(Uid partner, std::uint32_t stamp, bool& again);
    HistoryEntry& touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint, bool& again);
    /// The vector to insert into, created if there is none.
    std::vector<HistoryEntry>& ensure();

    static inline std::vector<HistoryEntry> const kNoEntries{}; // constant-initialised
    /// Null when empty (invariant: never points to an empty vector).
    std::unique_ptr<std::vector<HistoryEntry>> m_entries;
};

} // namespace regolith::particles
