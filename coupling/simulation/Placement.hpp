#pragma once
/// Where the blocks of a run live and this rank's grains on them (docs/design.md, "The time
/// step"): the forest of leaves, which carries the grid fields, the load balance and the block
/// output, and the particles' subdomains cut from the same assignment (sync.subdomains: each
/// rank's blocks merged into cuboids by default, so that blocks of one rank share no face the
/// synchronisation must cross).
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <memory>

namespace regolith::coupling {

/// The particles refer to the particle forest, so the three move together; a rebalance
/// replaces the objects' contents in place, and what refers to them sees the new assignment.
struct Placement {
    domain::ForestSpec spec; ///< what the forest is made of (a run's splits refine it)
    std::unique_ptr<domain::BlockForest> forest;         ///< one block per leaf
    std::unique_ptr<domain::BlockForest> particleForest; ///< the particles' subdomains
    std::unique_ptr<particles::LocalParticles> local;    ///< this rank's grains, on particleForest
};

/// The forest of `spec` with its blocks assigned to the ranks along the Hilbert curve by
/// `weight` (none: equal), its particle subdomains cut by `subdomains`, and no grains. Not
/// collective (every rank builds the same global set-up).
[[nodiscard]] Placement placeBlocks(core::Comm const& comm, domain::ForestSpec const& spec,
                                    domain::BlockWeight const& weight,
                                    domain::Subdomains subdomains);

} // namespace regolith::coupling
