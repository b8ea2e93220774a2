#pragma once
/// Block weights for the block -> rank assignment of a coupled run (docs/design.md, "The time
/// step": one forest, one assignment for particles and grid fields). The particle module's cost of
/// a block grows with its grains and their contacts, the grid module's with its cells, so a block
/// weighs
///
///     w_b = 1 + grainWeight * grains_b + contactWeight * contacts_b + cellWeight * cells_b
///
/// where contactWeight is the cost of a contact per step relative to a grain's without one
/// (measured: docs/balance.md), cellWeight that of one cell (docs/results.md, "Coupled runs"),
/// grainWeight 1 plus the self-gravity work a grain's rank does for it when that is known
/// (directGravityWeight), and the 1 spreads empty blocks evenly over the ranks. The contacts are
/// given per copy (particles::ContactCounts: during a run those of the last force computation,
/// DemStep::contactsOfLastPass; at a start the history entries stamped at its step,
/// LocalParticles::contactsStamped). With equal counts in every block the weights are equal and
/// the assignment is the uniform one.
#include "core/mpi/Comm.hpp"
#include "domain/Block.hpp"
#include "domain/ForestBuilder.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace regolith::coupling {

struct BlockLoadModel {
    std::array<int, 3> cellsPerBlock{0, 0, 0}; ///< 0: the run has no grid field
    double cellWeight = 0.0;                   ///< cost of a cell relative to a grain
    double contactWeight = kContactWeight;     ///< cost of a contact relative to a grain
    double grainWeight = 1.0; ///< cost of a grain, with the self-gravity attributed to it

    /// A settled pile's step costs 7.2-8.1x a falling gas's per grain with 2.5 contacts per
    /// grain (scenes/settling-gas.toml on one rank; docs/balance.md).
    static constexpr double kContactWeight = 2.5;
    /// One pair of the direct self-gravity sum (double-double, gravity/direct) costs 0.04 of
    /// a falling grain's step (scenes/cold-collapse.toml against scenes/settling-gas.toml on
    /// one rank; docs/balance.md).
    static constexpr double kDirectPairWeight = 0.04;

    /// w_b of a block holding `load`.
    [[nodiscard]] double weight(particles::LocalParticles::LeafLoad const& load) const;
};

/// grainWeight when the direct sum evaluates the field of all `grains` of the run at each
/// grain every `updateEvery` steps: its rank's work for a grain is grains / updateEvery
/// pairs per step (the ring pass: O(N^2 / P) per rank, gravity/direct/DirectSum.hpp).
[[nodiscard]] double directGravityWeight(double grains, double updateEvery);

/// The imbalance of the ranks' loads, max / mean (1: even; 1 also when there is no load).
/// COLLECTIVE.
[[nodiscard]] double loadImbalance(core::Comm const& comm, double load);

/// How even the ranks' loads are, and how even whole blocks can make them.
struct LoadSpread {
    double imbalance = 1.0; ///< max / mean of the ranks' loads
    /// The heaviest block over the mean load of a rank: no assignment of whole blocks reaches
    /// an imbalance below it (1 when there is no load).
    double blockFloor = 1.0;
};

/// The spread of the loads of the blocks `local` holds, its copies' contacts `contacts` ({1, 1}
/// on one rank). COLLECTIVE (two all-reductions).
[[nodiscard]] LoadSpread loadSpread(core::Comm const& comm, particles::LocalParticles const& local,
                                    particles::ContactCounts const& contacts,
                                    BlockLoadModel const& model);

/// Calls `f(leaf, storage, i, contacts)` for every master `i` of `local` (in `storage`) with
/// the index of the leaf of `builder`'s forest holding its centre and its entry of `contacts`;
/// the forest need not be the one the grains live on. Not collective.
template <class F>
void forEachMasterInLeaf(particles::LocalParticles const& local,
                         particles::ContactCounts const& contacts,
                         domain::ForestBuilder const& builder, F&& f) {
    local.requireCountsCover(contacts);
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        particles::ParticleStorage const& ps = blocks[b].particles;
        ps.forEachMaster([&](std::size_t i) {
            auto const at = builder.geometry().locate(ps.position(i));
            if (at) // a master lies in the domain
                f(builder.leafAt(at->cell), ps, i, contacts[b][i]);
        });
    }
}

/// The grains and contacts of every leaf of `builder`'s forest, in its curve order, from the
/// masters of `local` (and `contacts`) binned by their positions: the same on every rank.
/// COLLECTIVE (one all-reduction of two numbers per leaf).
[[nodiscard]] std::vector<particles::LocalParticles::LeafLoad>
leafCounts(core::Comm const& comm, particles::LocalParticles const& local,
           particles::ContactCounts const& contacts, domain::ForestBuilder const& builder);

/// The load of every leaf of `builder`'s forest, in its curve order, from the masters of
/// `local` (and their contacts) binned by their positions: the same on every rank. The forest
/// need not be the one the grains live on (a finer one, BlockSplit.hpp). COLLECTIVE (one
/// all-reduction of two numbers per leaf).
[[nodiscard]] std::vector<double> leafLoads(core::Comm const& comm,
                                            particles::LocalParticles const& local,
                                            particles::ContactCounts const& contacts,
                                            BlockLoadModel const& model,
                                            domain::ForestBuilder const& builder);

/// The weight function of every block of the forest `spec` makes, from the masters (and their
/// contacts) each block would hold now (leafLoads). Blocks are matched by (box, level), which
/// the same specification reproduces exactly. COLLECTIVE; the result is local.
[[nodiscard]] domain::BlockWeight grainAndCellWeights(core::Comm const& comm,
                                                      particles::LocalParticles const& local,
                                                      particles::ContactCounts const& contacts,
                                                      BlockLoadModel const& model,
                                                      domain::ForestSpec const& spec);

} // namespace regolith::coupling
