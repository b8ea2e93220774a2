#pragma once
/// A checksum of a simulation state, fed value by value in a canonical order (particles
/// sorted by uid), printed as 16 hex digits. Bitwise-identical input gives the same digest on
/// any number of ranks; any changed bit changes it with overwhelming probability.
#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace regolith::apps {

/// 64-bit FNV-1a (Fowler, Noll, Vo; IETF draft-eastlake-fnv). Not cryptographic: it detects
/// differences, it does not resist forgery.
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

} // namespace regolith::apps
