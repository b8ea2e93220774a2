#pragma once
/// Checksums of a simulation state. Bitwise-identical states give the same digest on any
/// number of ranks and for any distribution of the particles over them; any changed bit
/// changes it with overwhelming probability. Printed as 16 hex digits.
#include "apps/common/MasterRecord.hpp"
#include "core/mpi/Comm.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace regolith::apps {

/// 64-bit FNV-1a (Fowler, Noll, Vo; IETF draft-eastlake-fnv), fed value by value in a
/// canonical order. Not cryptographic: it detects differences, it does not resist forgery.
class StateChecksum {
public:
    void addBytes(void const* data, std::size_t n) {
        auto const* p = static_cast<unsigned char const*>(data);
        for (std::size_t i = 0; i < n; ++i) {
            m_hash ^= p[i];
            m_hash *= kPrime;
        }
    }
    void add(std::uint64_t x) { addBytes(&x, sizeof x); }
    /// Adds the bit pattern of x (so -0.0 and 0.0 differ, as they do in the state).
    void add(double x) { add(std::bit_cast<std::uint64_t>(x)); }

    [[nodiscard]] std::uint64_t value() const { return m_hash; }
    [[nodiscard]] std::string hex() const { return fmt::format("{:016x}", m_hash); }

private:
    static constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
    static constexpr std::uint64_t kPrime = 0x100000001b3ULL;
    std::uint64_t m_hash = kOffsetBasis;
};

/// The digest of one master: FNV-1a over its uid and the bit patterns of position, velocity,
/// angular velocity, radius and mass (the dump's column order), then MurmurHash3's 64-bit
/// finaliser (fmix64, Appleby) so that every input bit reaches every output bit before the
/// digests are summed. Not collective.
[[nodiscard]] std::uint64_t masterDigest(MasterRecord const& m);

/// Checksum of the masters of all ranks, independent of how they are distributed and
/// ordered: the multiset hash "MSet-Add-Hash" of Clarke et al. (2003, "Incremental multiset
/// hash functions and their application to memory integrity checking", ASIACRYPT), i.e. the
/// sum modulo 2^64 of masterDigest over all masters (exact integer arithmetic, so the MPI
/// reduction order does not matter), folded with the global count by FNV-1a. So it is a
/// function of the uid-sorted state alone, computed without gathering it; a master lost or
/// doubled, or one changed bit, changes it (but for a ~2^-64 chance). 16 hex digits, the same
/// on every rank. COLLECTIVE over `comm`.
[[nodiscard]] std::string stateChecksum(core::Comm const& comm,
                                        std::span<MasterRecord const> local);
/// The same from a source of masters. COLLECTIVE over `comm`.
[[nodiscard]] std::string stateChecksumFrom(core::Comm const& comm, MasterSource const& local);

} // namespace regolith::apps
