#pragma once
/// The Philox4x32-10 block function: a keyed bijection of 128-bit counters, from
/// J. K. Salmon, M. A. Moraes, R. O. Dror, D. E. Shaw, "Parallel random numbers: as easy as
/// 1, 2, 3", SC'11 (multipliers and Weyl key increments as in the paper and in Random123's
/// philox.h). Output is checked against Random123's kat_vectors in the tests.
#include <array>
#include <cstdint>

namespace regolith::core::random {

using PhiloxCounter = std::array<std::uint32_t, 4>;
using PhiloxKey = std::array<std::uint32_t, 2>;

inline constexpr std::uint32_t kPhiloxM0 = 0xD2511F53u; ///< round multiplier for word 0
inline constexpr std::uint32_t kPhiloxM1 = 0xCD9E8D57u; ///< round multiplier for word 2
inline constexpr std::uint32_t kPhiloxW0 = 0x9E3779B9u; ///< key bump, golden ratio
inline constexpr std::uint32_t kPhiloxW1 = 0xBB67AE85u; ///< key bump, sqrt(3) - 1
inline constexpr int kPhiloxRounds = 10;

/// One Philox round: two 32x32->64 multiplications, the high halves xored with the other
/// words and the key, then a word permutation.
constexpr PhiloxCounter philoxRound(PhiloxCounter const& c, PhiloxKey const& k) {
    std::uint64_t const p0 = std::uint64_t{kPhiloxM0} * c[0];
    std::uint64_t const p1 = std::uint64_t{kPhiloxM1} * c[2];
    auto const hi0 = static_cast<std::uint32_t>(p0 >> 32);
    auto const lo0 = static_cast<std::uint32_t>(p0);
    auto const hi1 = static_cast<std::uint32_t>(p1 >> 32);
    auto const lo1 = static_cast<std::uint32_t>(p1);
    return {hi1 ^ c[1] ^ k[0], lo1, hi0 ^ c[3] ^ k[1], lo0};
}

/// Philox4x32-10 of `counter` under `key`: 10 rounds, the key bumped between rounds.
constexpr PhiloxCounter philox4x32(PhiloxCounter counter, PhiloxKey key) {
    counter = philoxRound(counter, key);
    for (int r = 1; r < kPhiloxRounds; ++r) {
        key[0] += kPhiloxW0;
        key[1] += kPhiloxW1;
        counter = philoxRound(counter, key);
    }
    return counter;
}

} // namespace regolith::core::random
