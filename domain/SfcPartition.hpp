#pragma once
/// Cutting a weighted sequence (blocks along the space-filling curve) into contiguous chunks,
/// one per rank.
#include <span>
#include <vector>

namespace regolith::domain {

/// Owner rank in [0, parts) of every element of `weights`, non-decreasing along the sequence
/// (each rank gets one contiguous chunk, possibly empty). Element i goes to the rank whose
/// slice [r W / P, (r + 1) W / P) of the total weight W holds the midpoint of its prefix
/// interval [S_i, S_i + w_i). This is the prefix-sum cut of a space-filling curve of Pilkington
/// and Baden ("Dynamic partitioning of non-uniform structured workloads with spacefilling
/// curves", IEEE TPDS 7(3), 1996), with the element midpoint deciding which side of a cut an
/// element falls on. Each chunk then starts within w_max / 2 of its ideal cut, so every rank's
/// load differs from W / P by less than the largest element weight w_max. Then single
/// elements move across the cuts while that relieves the heavier of two neighbouring parts
/// (the lighter staying below what the heavier weighed): this keeps the bound, never raises
/// the largest load, and lowers it where the midpoints cut unluckily (blocks of very
/// different weights: a settled pile next to empty blocks).
/// If all weights are zero, the elements are counted instead (every weight taken as 1).
/// Throws core::InputError if a weight is negative or not finite, or parts < 1.
/// Deterministic: the same input gives the same owners on every rank. Not collective.
[[nodiscard]] std::vector<int> partitionCurve(std::span<double const> weights, int parts);

} // namespace regolith::domain
