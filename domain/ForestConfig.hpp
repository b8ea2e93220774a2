#pragma once
/// The `[domain]` section of a scene file, parsed into a ForestSpec.
#include "core/config/ConfigTable.hpp"
#include "domain/ForestSpec.hpp"

namespace regolith::domain {

/// Parses `section` (the scene's `[domain]` table):
///   min = [x, y, z], max = [x, y, z]      required; finite; max > min on every axis
///   blocks = [nx, ny, nz]                 root blocks per axis, default [1, 1, 1]; each > 0
///   periodic = [bx, by, bz]               default [false, false, false]
///   refine = [{ min = [..], max = [..], level = L }, ...]   optional static refinement;
///                                         the region lies inside the domain, min <= max,
///                                         L in [0, kMaxRefineLevel]
///   cells_per_block = [cx, cy, cz]        grid cells per block, default [0, 0, 0] (no grid);
///                                         all zero or all positive
/// Limits are those of domain::validate (SpecValidation.hpp), checked here first so that the
/// message names the file, line and key. Throws core::InputError. Not collective; marks the
/// keys it reads (the caller runs rejectUnknownKeys on the whole scene afterwards).
[[nodiscard]] ForestSpec parseForestSpec(core::ConfigTable const& section);

} // namespace regolith::domain
