#pragma once
/// SOS's per-block sent-cache (Eibl & Ruede 2018, sec. 3.3) as one sorted flat vector: the
/// copies this block has already ordered its neighbours to create, so that a shadow does not
/// re-send creation orders every call.
#include "particles/storage/CopyImage.hpp"
#include "particles/storage/Uid.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace regolith::particles {

/// One creation order this block sent: copy (uid, image) on the neighbour block `block`.
/// Its field order is the wire format of the ForgetSent record.
struct SentEntry {
    std::uint64_t block = 0; ///< the neighbour block (BlockId::raw)
    Uid uid = kInvalidUid;
    CopyImage image = kNoImage; ///< the image of the copy on the neighbour
    friend bool operator==(SentEntry const& a, SentEntry const& b) {
        return a.block == b.block && a.uid == b.uid && sameImage(a.image, b.image);
    }
};

/// The set of SentEntry of one block, sorted by (uid, block, image) in one vector: the
/// entries of a grain are contiguous, so forgetting or shifting a grain is a binary search and
/// a short range, not a walk over the whole set (which a std::set keyed by block needed), and
/// a lookup touches one cache-friendly array with no node per entry. A block holds few
/// entries (those of grains near its faces that spread), so the O(n) shift of an insertion
/// costs less than the allocations of a node-based set. Local (no communication).
class SentCache {
public:
    /// Adds `e`; false (and no change) if it was present already.
    bool insert(SentEntry const& e);
    [[nodiscard]] bool contains(SentEntry const& e) const;
    /// Removes `e`; false if absent.
    bool erase(SentEntry const& e);
    /// Removes every entry of `uid` (its local copy is gone, or it stopped spreading).
    void forget(Uid uid);
    /// Moves every entry of `uid` to image - delta (the grain's frame moved by delta whole
    /// periods: its master crossed a periodic boundary).
    void shift(Uid uid, CopyImage const& delta);

    [[nodiscard]] std::size_t size() const { return m_entries.size(); }
    [[nodiscard]] bool empty() const { return m_entries.empty(); }
    void clear() { m_entries.clear(); }
    /// The entries in ascending (uid, block, image).
    [[nodiscard]] std::span<SentEntry const> entries() const { return m_entries; }

private:
    std::vector<SentEntry> m_entries; ///< sorted by (uid, block, image), no duplicates
};

} // namespace regolith::particles
