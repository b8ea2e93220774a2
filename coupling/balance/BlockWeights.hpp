#pragma once
/// Block weights for the block -> rank assignment of a coupled run (DESIGN.md: one forest, one
/// assignment for particles and grid fields). The particle module's cost of a block grows with
/// its grains, the grid module's with its cells, so a block weighs
///
///     w_b = 1 + grains_b + cellWeight * cells_b
///
/// where cellWeight is the cost of one cell per step relative to one grain per step (measured:
/// docs/results.md, "Coupled runs") and the 1 spreads empty blocks evenly over the ranks. With
/// equal counts in every block the weights are equal and the assignment is the uniform one.
#include "core/mpi/Comm.hpp"
#include "domain/Block.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <array>
#include <cstddef>

namespace regolith::coupling {

struct BlockLoadModel {
    std::array<int, 3> cellsPerBlock{0, 0, 0}; ///< 0: the run has no grid field
    double cellWeight = 0.0;                   ///< cost of a cell relative to a grain

    /// w_b of a block holding `grains` masters.
    [[nodiscard]] double weight(std::size_t grains) const;
};

/// The load of this rank: the weights of the forest blocks (leaves) its particle blocks
/// cover, summed. Local.
[[nodiscard]] double rankLoad(particles::LocalParticles const& local, BlockLoadModel const& model);

/// The imbalance of the ranks' loads, max / mean (1: even; 1 also when there is no load).
/// COLLECTIVE.
[[nodiscard]] double loadImbalance(core::Comm const& comm, double load);

/// The weight function of every block of `local`'s forest, from the masters each block holds
/// now. Blocks are matched by (box, level), which the same forest specification reproduces
/// exactly. COLLECTIVE (one all-gather of O(global blocks) doubles); the result is local.
[[nodiscard]] domain::BlockWeight grainAndCellWeights(core::Comm const& comm,
                                                      particles::LocalParticles const& local,
                                                      BlockLoadModel const& model);

} // namespace regolith::coupling
