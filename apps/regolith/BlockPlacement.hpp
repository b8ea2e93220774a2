#pragma once
/// Where the blocks of a run live: the forest is built once with every block weighing the
/// same (grains are generated on it), then re-assigned by its load at the start (grains and
/// grid cells, coupling::grainAndCellWeights) unless the scene says `domain.balance =
/// "blocks"`. Particles and grid fields share this one assignment (docs/design.md, "The time
/// step").
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/balance/BlockWeights.hpp"
#include "coupling/simulation/Placement.hpp"

#include <algorithm>
#include <functional>

namespace regolith::apps {

/// The forest of `scene` with equal block weights and no particles. Not collective.
[[nodiscard]] coupling::Placement uniformPlacement(core::Comm const& comm,
                                                   SceneDescription const& scene);

/// The blocks' load model of `scene`: grains and their contacts, cells when its gravity uses
/// a grid, and the direct sum's pairs when it updates on a fixed schedule (it then costs
/// most of a step: coupling::directGravityWeight). COLLECTIVE (counts the run's grains).
[[nodiscard]] coupling::BlockLoadModel loadModel(core::Comm const& comm,
                                                 SceneDescription const& scene,
                                                 particles::LocalParticles const& local);

/// Whether a new cut is worth moving the grains, from the imbalance of the ranks' loads
/// (max / mean) it would give.
using WorthMoving = std::function<bool(double after)>;

/// The share of a rank's mean load above which a block splits: half of balance.threshold - 1,
/// at least a twentieth (coupling/balance/BlockSplit.hpp: below threshold - 1 the cut that
/// follows comes within the threshold; half leaves room for the load to keep gathering).
[[nodiscard]] inline double splitShare(double threshold) {
    return std::max(0.5 * (threshold - 1.0), 0.05);
}

/// Re-assigns the blocks of `placement` by the load of the masters it holds (and the cells,
/// when the scene's gravity uses a grid), splitting the heavy blocks where no cut of whole
/// blocks reaches 1 + (balance.threshold - 1) / 2 and balance.split_levels allows, if one block
/// alone outweighs that or the split's cut costs less with its shadows counted
/// (coupling::splitHeavyBlocks), and moves every master, with its
/// force, torque and contact history, to its new owner. The forests and the particles are replaced
/// in place (references to them stay valid and see the new assignment; what was built on the old
/// one, the synchronisation, DemStep's lists, a grid, must be relocated). Keeps `placement` when
/// the assignment does not change (equal loads, or domain.balance = "blocks") or
/// `worthMoving` (if given) says no. `contacts`: each copy's contacts (BlockWeights.hpp); the
/// grains' state must be complete (DemStep::completeStep). Returns whether the blocks moved.
/// COLLECTIVE.
bool balanceByLoad(core::Comm const& comm, SceneDescription const& scene,
                   coupling::Placement& placement, particles::ContactCounts const& contacts,
                   WorthMoving const& worthMoving = {});

} // namespace regolith::apps
