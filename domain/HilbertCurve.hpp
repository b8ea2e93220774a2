#pragma once
/// The three-dimensional Hilbert curve on a 2^bits x 2^bits x 2^bits grid of cells, used to
/// order the root blocks before they are cut into per-rank chunks.
#include <array>
#include <cstdint>

namespace regolith::domain {

/// Largest grid exponent whose curve index fits in 64 bits (3 * 21 = 63 bits).
inline constexpr int kMaxHilbertBits = 21;

/// Position of `cell` (each coordinate in [0, 2^bits)) along the Hilbert curve through the
/// 2^bits cube, in [0, 8^bits). Consecutive positions are face-adjacent cells.
/// Skilling's transpose algorithm: J. Skilling, "Programming the Hilbert curve",
/// AIP Conf. Proc. 707, 381 (2004). Pre: 0 <= bits <= kMaxHilbertBits (throws core::Error).
[[nodiscard]] std::uint64_t hilbertIndex(std::array<std::uint32_t, 3> cell, int bits);

/// Inverse of hilbertIndex: the cell at position `index` in [0, 8^bits).
[[nodiscard]] std::array<std::uint32_t, 3> hilbertCell(std::uint64_t index, int bits);

/// Smallest exponent m with 2^m >= n for every extent n (the enclosing power-of-two grid).
/// Pre: every extent >= 1.
[[nodiscard]] int hilbertBitsFor(std::array<int, 3> extent);

} // namespace regolith::domain
