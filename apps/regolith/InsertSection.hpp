#pragma once
/// The scene's [[insert]] entries (docs/guide/walls.md): grains poured in during the run.
#include "core/config/ConfigTable.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/generators/InsertSpec.hpp"

namespace regolith::apps {

/// One [[insert]] entry: region = { min, max } (a box) or { base, axis, radius, length } (a
/// cylinder), count, rate (grains per time; absent: all at once), every (steps between
/// batches, default 100), radius (r or [min, max], uniform), density, velocity, type, seed,
/// attempts. Throws core::InputError naming file, line and key for a value out of range, a
/// region outside `forest`'s domain or too small for the largest grain, or a batch denser
/// than random placement can reach (checkBatchDensity). Not collective.
[[nodiscard]] particles::InsertSpec parseInsert(core::ConfigTable const& entry,
                                                domain::ForestSpec const& forest);

/// The most grains one batch of `spec` asks for with time step `dt`: count without a rate,
/// else rate x every x dt rounded up (at most count; a product within a relative 1e-12 above a
/// whole number is taken as it).
[[nodiscard]] std::int64_t batchSize(particles::InsertSpec const& spec, double dt);

/// Throws core::InputError ("insert[k].count: ..." or ".rate") if one batch of the smallest
/// grains would fill more of the region than random sequential addition can
/// (particles::kRandomAdditionLimit): they cannot all be placed without overlap. Not
/// collective.
void checkBatchDensity(particles::InsertSpec const& spec, std::size_t index, double dt);

} // namespace regolith::apps
