#pragma once
/// Checks a ForestSpec before a forest is built from it.
#include "domain/ForestSpec.hpp"

namespace regolith::domain {

/// Deepest static refinement level a scene may ask for (`domain.refine[i].level`).
inline constexpr int kMaxRefineLevel = 8;
/// Most root blocks per axis (the Hilbert index of the root grid must fit in 64 bits).
inline constexpr int kMaxRootBlocksPerAxis = 1 << 21;

/// Throws core::InputError with a message naming the offending scene key if
///  - domain.min / domain.max are not finite or max <= min on an axis,
///  - domain.blocks has an entry <= 0 or above kMaxRootBlocksPerAxis, or more root blocks in
///    total than a BlockId can number (BlockId::kMaxRootIndex + 1),
///  - domain.refine[i].level is outside [0, kMaxRefineLevel],
///  - domain.refine[i].region is not finite, has max < min, or is not inside the domain,
///  - domain.cells_per_block mixes zero and non-zero entries or has a negative one.
/// Every rank reads the same spec, so every rank throws the same error. Not collective.
void validate(ForestSpec const& spec);

} // namespace regolith::domain
