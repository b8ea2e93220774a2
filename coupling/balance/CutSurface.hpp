#pragma once
/// What a cut of the blocks costs the ranks beyond their loads: the shadows on their surface.
/// The particles' synchronisation merges a rank's blocks into cuboids (domain/RankBoxes.hpp)
/// and copies a grain into every other cuboid its ball reaches, so a cut through finer blocks,
/// whose regions are more ragged, copies more grains. A shadow costs its rank the grain's
/// contact work (its pairs with the grains there, its state copied every step), not the
/// self-gravity attributed to the grain, which the master's rank does:
///
///     cost_r = load_r + sum over the shadows s on r of (1 + contactWeight * contacts_s)
///
/// (load_r in the units of BlockLoadModel; contacts_s the grain's contacts, BlockWeights.hpp). A
/// grain is taken to reach the cuboids holding one of 26 points of its surface (along the axes, the
/// face and the space diagonals).
#include "coupling/balance/BlockWeights.hpp"

#include <span>
#include <vector>

namespace regolith::coupling {

/// cost_r of every rank r when the leaves of `builder`'s forest, weighing `load` (in its curve
/// order), go to the ranks `owner`. From the masters of `local` binned by their positions: the
/// same on every rank (the shadows' weights are multiples of 1/2, summed exactly).
/// COLLECTIVE (one all-reduction of a number per rank).
[[nodiscard]] std::vector<double>
rankCosts(core::Comm const& comm, particles::LocalParticles const& local,
          particles::ContactCounts const& contacts, BlockLoadModel const& model,
          domain::ForestBuilder const& builder, std::span<double const> load,
          std::span<int const> owner);

} // namespace regolith::coupling
