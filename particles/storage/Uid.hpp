#pragma once
/// Globally unique particle ids made without communication: the creating rank in the high
/// bits, a per-rank counter in the low bits (as mesa_pd's `UniqueID`, but as one integer so it
/// sorts, hashes and travels as 8 bytes).
#include "core/Error.hpp"

#include <cstdint>
#include <string>

namespace regolith::particles {

/// A particle's (or wall's) id, unique over all ranks and the whole run.
using Uid = std::uint64_t;

inline constexpr int kUidCounterBits = 40;                ///< up to ~1.1e12 ids per rank
inline constexpr int kUidRankBits = 64 - kUidCounterBits; ///< up to ~1.7e7 ranks
inline constexpr std::uint64_t kUidCounterMask = (std::uint64_t{1} << kUidCounterBits) - 1;
/// The highest rank field is reserved for global objects that no rank creates (walls).
inline constexpr int kGlobalObjectRank = (1 << kUidRankBits) - 1;
/// Ranks from here up to kGlobalObjectRank - 1 create no uids: with the top bit flipped, an id
/// names the same partner's rolling spring in a contact history (rollingKey), which must not
/// be another object's id.
inline constexpr int kFirstReservedRank = (1 << (kUidRankBits - 1)) - 1;
/// Never a valid id of anything; used as "none".
inline constexpr Uid kInvalidUid = ~Uid{0};

/// `(rank << 40) | counter`. Throws core::Error if `rank` is outside [0, kFirstReservedRank)
/// and not kGlobalObjectRank
/// or `counter` does not fit in 40 bits (or the result would be kInvalidUid).
constexpr Uid makeUid(int rank, std::uint64_t counter) {
    if (rank < 0 || rank > kGlobalObjectRank ||
        (rank >= kFirstReservedRank && rank != kGlobalObjectRank))
        throw core::Error("makeUid: rank " + std::to_string(rank) + " does not fit in " +
                          std::to_string(kUidRankBits) + " bits");
    if (counter > kUidCounterMask || (rank == kGlobalObjectRank && counter == kUidCounterMask))
        throw core::Error("makeUid: counter " + std::to_string(counter) + " does not fit in " +
                          std::to_string(kUidCounterBits) + " bits");
    return (static_cast<Uid>(rank) << kUidCounterBits) | counter;
}

/// The key under which a contact history keeps the rolling spring (model C) of the contact
/// with `partner`, beside the tangential spring keyed by `partner` itself: the top bit
/// flipped, which is no object's id (kFirstReservedRank). A second entry rather than a wider
/// one: a rolling vector in every entry (40 -> 64 bytes) slowed the static lattice's contact
/// loop by ~12 % for scenes that do not use it.
constexpr Uid rollingKey(Uid partner) {
    return partner ^ (Uid{1} << 63);
}

/// The rank that created `uid`.
constexpr int uidRank(Uid uid) {
    return static_cast<int>(uid >> kUidCounterBits);
}
/// The creating rank's counter value of `uid`.
constexpr std::uint64_t uidCounter(Uid uid) {
    return uid & kUidCounterMask;
}

/// Hands out consecutive uids of one rank. Not thread-safe; one per rank (and per run: a
/// restart must continue from the largest counter it read back, see `UidGenerator(rank, next)`).
class UidGenerator {
public:
    /// Starts at `(rank, firstCounter)`. Throws core::Error for an invalid rank.
    explicit UidGenerator(int rank, std::uint64_t firstCounter = 0)
        : m_rank(rank)
        , m_next(firstCounter) {
        (void)makeUid(rank, 0);
    }
    /// The next unused uid; throws core::Error once the 40-bit counter is exhausted.
    Uid next() { return makeUid(m_rank, m_next++); }
    [[nodiscard]] int rank() const { return m_rank; }
    /// The counter the next call to `next()` will use.
    [[nodiscard]] std::uint64_t nextCounter() const { return m_next; }

private:
    int m_rank;
    std::uint64_t m_next;
};

} // namespace regolith::particles
