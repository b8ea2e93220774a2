#pragma once
/// The grid of ranks a scaling scenario lays its per-rank boxes on.
#include <array>

namespace regolith::apps {

/// The most cubic factorisation x * y * z = ranks with x >= y >= z (z = 1 for `axes` = 2, a
/// partitioning in x and y only, as the paper's dense scenario uses). Pre: ranks >= 1,
/// axes 2 or 3. E.g. 8 -> {2, 2, 2}, 12 -> {3, 2, 2}, 6 with 2 axes -> {3, 2, 1}.
[[nodiscard]] std::array<int, 3> rankGrid(int ranks, int axes = 3);

} // namespace regolith::apps
