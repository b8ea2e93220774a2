#pragma once
/// The tangential-spring history of one particle's contacts, keyed by partner uid, kept with
/// the particle so that it travels with it (docs/design.md, "The time step": whichever
/// block evaluates a contact finds its history). A pair's entry lives on the partner with the
/// smaller uid (the `i` of the canonical contact order); a sphere–wall entry lives on the sphere,
/// keyed by the wall's uid.
#include "core/math/Vec3.hpp"
#include "particles/storage/ThinList.hpp"
#include "particles/storage/Uid.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

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

/// A contact's tangential spring kept outside the grains' histories, beside a neighbour list's
/// pair (ContactDetector, "Springs kept beside the list"): a HistoryEntry without the partner
/// (the list knows it), 32 bytes instead of 40, read and written per pair and step.
struct KeptSpring {
    /// The stamp of a spring filled from an absent entry (no touch since).
    static constexpr std::uint32_t kUntouched = 0xffffffffu;
    core::Vec3 spring = core::Vec3::Zero();
    std::uint32_t stamp = kUntouched;
};

/// A small array of `HistoryEntry` sorted by partner uid: look-up is a binary search over a
/// handful of entries, iteration order is canonical (by uid), and an empty history costs no
/// heap memory.
///
/// Memory and access: every copy of every grain has one, and most (a sparse gas: nearly all)
/// are empty, so it is a single pointer (8 bytes), null while empty, to ONE heap block that
/// holds the entry count, the capacity and the entries (a ThinList). The contact loop touches a
/// history per contact, at scattered addresses: one block is one dependent load fewer than a
/// pointer to a std::vector (the vector object, then its buffer); the dense ramp's contact phase
/// ran 1.08x faster with it.
class ContactHistory {
public:
    /// The entry for `partner`, or nullptr.
    [[nodiscard]] HistoryEntry const* find(Uid partner) const;
    [[nodiscard]] HistoryEntry* find(Uid partner);
    /// find() that first tries slot `hint` (where the entry sat when last found).
    [[nodiscard]] HistoryEntry* find(Uid partner, std::uint8_t hint) {
        if (hint < m_entries.size() && m_entries[hint].partner == partner)
            return &m_entries[hint];
        return find(partner);
    }
    /// The entry for `partner` (created with a zero spring if absent), stamped with `stamp`.
    /// Passes are numbered consecutively: an entry found with a stamp below `stamp - 1` was not
    /// touched in the previous pass, so its contact broke since, and it starts again from a
    /// zero spring (as a new entry would: the synchronisation drops untouched entries only
    /// every few passes, ParticleSync::kHistoryPruneInterval).
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
        if (hint < m_entries.size() && m_entries[hint].partner == partner) [[likely]] {
            HistoryEntry& e = m_entries[hint];
            renew(e, stamp, again);
            return e;
        }
        return touchSlow(partner, stamp, hint, again);
    }
    /// Starts loading the entries into the cache (the prune calls it a few grains ahead).
    [[gnu::always_inline]] void prefetch() const { m_entries.prefetch(); }
    /// Inserts or overwrites an entry (used when history arrives with a particle).
    void set(HistoryEntry const& entry);
    /// Replaces every entry by `entries` (sorted by partner uid, unique: another history's
    /// entries), reusing the heap block if it is large enough: a shadow takes its master's
    /// history every step.
    void assign(std::span<HistoryEntry const> entries) {
        m_entries.assign(entries.begin(), entries.end());
    }
    /// Removes the entry for `partner`; returns whether there was one.
    bool erase(Uid partner);
    /// Drops every entry whose stamp differs from `stamp`: the contacts not evaluated in the
    /// current pass are broken. Returns how many were dropped.
    std::size_t keepOnly(std::uint32_t stamp) {
        return m_entries.empty() ? 0 : keepOnlySlow(stamp); // most grains: no contact
    }

    [[nodiscard]] std::size_t size() const { return m_entries.size(); }
    [[nodiscard]] bool empty() const { return m_entries.empty(); }
    void clear() { m_entries.clear(); }
    [[nodiscard]] HistoryEntry const* begin() const { return m_entries.begin(); }
    [[nodiscard]] HistoryEntry const* end() const { return m_entries.end(); }
    /// Heap bytes held (capacity, not size).
    [[nodiscard]] std::size_t heapBytes() const { return m_entries.heapBytes(); }
    /// The entries in uid order (for packing into messages).
    [[nodiscard]] std::span<HistoryEntry const> entries() const {
        return {m_entries.begin(), m_entries.size()};
    }

    /// Whether an entry stamped `last` keeps its spring when touched in pass `stamp`: it was
    /// touched in this pass or the previous one (else its contact broke since, and the spring
    /// restarts from zero).
    [[nodiscard]] static bool continues(std::uint32_t last, std::uint32_t stamp) {
        return last == stamp || last + 1 == stamp;
    }

private:
    /// Stamps a found entry (see continues). `again`: it had been stamped `stamp` already.
    static void renew(HistoryEntry& e, std::uint32_t stamp, bool& again) {
        again = e.stamp == stamp;
        if (!continues(e.stamp, stamp))
            e.spring = core::Vec3::Zero();
        e.stamp = stamp;
    }
    std::size_t keepOnlySlow(std::uint32_t stamp);
    /// touch() by search; `again` as in the hinted touch (left alone for a new entry).
    HistoryEntry& touchAt(Uid partner, std::uint32_t stamp, bool& again);
    HistoryEntry& touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint, bool& again);
    /// Where `partner` is or would go: the first entry not below it.
    [[nodiscard]] std::size_t lowerBound(Uid partner) const;

    ThinList<HistoryEntry> m_entries; ///< sorted by partner uid
};

} // namespace regolith::particles
