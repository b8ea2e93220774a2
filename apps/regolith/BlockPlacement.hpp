#pragma once
/// Where the blocks of a run live: the forest is built once with every block weighing the
/// same (grains are generated on it), then re-assigned by its load at the start (grains and
/// grid cells, coupling::grainAndCellWeights) unless the scene says `domain.balance =
/// "blocks"`. Particles and grid fields share this one assignment (DESIGN.md).
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <memory>

namespace regolith::apps {

/// The forest of the run and this rank's particles on it (the particles refer to the forest,
/// so both move together). The particles see the same assignment cut into their own
/// subdomains (sync.subdomains: by default each rank's blocks merged into cuboids, so that
/// the blocks of one rank share no face the synchronisation must cross).
struct BlockPlacement {
    std::unique_ptr<domain::BlockForest> forest;         ///< one block per leaf: grid, output
    std::unique_ptr<domain::BlockForest> particleForest; ///< the particles' subdomains
    std::unique_ptr<particles::LocalParticles> local;    ///< on particleForest
};

/// The forest of `scene` with equal block weights and no particles. Not collective.
[[nodiscard]] BlockPlacement uniformPlacement(core::Comm const& comm,
                                              SceneDescription const& scene);

/// Re-assigns the blocks of `placement` by the load of the masters it holds (and the cells,
/// when the scene's gravity uses a grid) and moves every master, with its force, torque and
/// contact history, to its new owner. Keeps `placement` when the assignment does not change
/// (equal loads, or domain.balance = "blocks"). Returns whether it changed. COLLECTIVE.
bool balanceByLoad(core::Comm const& comm, SceneDescription const& scene,
                   BlockPlacement& placement);

} // namespace regolith::apps
