#pragma once
/// The "auto" keys of [balance] (docs/balance.md), resolved before the start's assignment
/// (which splits blocks too): they change where the work runs, not the trajectory.
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"

#include <vector>

namespace regolith::apps {

/// balance.split_levels = "auto" where the blocks can split: a block may become 16 times
/// finer along each axis than the scene's (enough for a cloud collapsing to a tenth of its
/// radius, docs/results.md "Load balance").
inline constexpr std::int64_t kAutoSplitLevels = 4;

/// domain.blocks where the scene gives none: on more than one rank one root block per rank,
/// the grid of ranks[0] x ranks[1] x ranks[2] = ranks whose blocks have the least surface
/// (LAMMPS's `processors * * *`), so that the ranks' regions are cuboids cut across the
/// domain's longest extents; [1, 1, 1] on one rank, and where the blocks fix more than where
/// the work runs: grid cells per block (domain.cells_per_block, a grid gravity method) or
/// refinement levels counted from the root blocks ([[domain.refine]]). Not collective.
[[nodiscard]] AutoChoice resolveRootBlocks(core::Comm const& comm, SceneDescription& scene);

/// Resolves balance.every and balance.split_levels where "auto" and returns the decisions:
///  - balance.every: autoBalanceEvery(time.steps) on more than one rank (0 on one, or with
///    domain.balance = "blocks"); an explicit interval above 0 on one rank or with
///    domain.balance = "blocks" is refused;
///  - balance.split_levels: kAutoSplitLevels where the blocks are re-cut during the run, the
///    gravity uses no grid and sync.method is not "nns", else 0; explicit levels above 0
///    where they cannot split are refused.
/// Refusals throw core::InputError on every rank. Not collective.
[[nodiscard]] std::vector<AutoChoice> resolveBalanceChoices(core::Comm const& comm,
                                                            SceneDescription& scene);

} // namespace regolith::apps
