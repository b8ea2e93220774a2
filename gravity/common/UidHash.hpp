#pragma once
/// A hash of grain uids that spreads them over the whole range: uids are (rank << 40) |
/// counter, whose low bits alone would pick the grains of one creating rank, or pile them onto
/// few ranks. Used to pick samples of grains that are the same on any layout.
#include <cstdint>

namespace regolith::gravity {

/// SplitMix64's finaliser (Steele, Lea & Flood 2014).
[[nodiscard]] constexpr std::uint64_t uidHash(std::uint64_t z) {
    z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31U);
}

} // namespace regolith::gravity
