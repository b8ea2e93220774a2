#pragma once
/// Parallel Barnes–Hut self-gravity (`gravity.self = "tree"`): monopole +
/// quadrupole cells about the centre of mass, the offset-guarded opening test (Octree.hpp),
/// grouped walks with batched interaction lists (InteractionList.hpp) and locally essential
/// trees between ranks (LocallyEssentialTree.hpp).
///
/// One update: every rank builds the octree of its own grains; the ranks all-gather the
/// boxes that hold their grains (one tight box per block box given, or one tight box); each
/// rank prunes its tree for every other rank's boxes and sends the result by sparse exchange
/// (NBX); then every group of local targets walks its own tree and every received tree.
#include "core/math/AABB.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/tree/TreeOptions.hpp"

#include <span>
#include <vector>

namespace regolith::gravity::tree {

/// What the last evaluation did on this rank.
struct TreeStats {
    long long cellInteractions = 0;  ///< target–multipole evaluations
    long long grainInteractions = 0; ///< target–grain evaluations
    long long nodesSent = 0;         ///< tree nodes sent to other ranks
    long long grainsSent = 0;        ///< grains sent to other ranks
    long long bytesSent = 0;         ///< payload bytes sent to other ranks
};

class BarnesHut {
public:
    /// Validates `options` (core::InputError naming the key, e.g. `gravity.theta`).
    /// COLLECTIVE over `comm` (duplicates it for the exchange).
    BarnesHut(core::Comm const& comm, TreeOptions const& options);

    /// Field at the local grains due to the grains of all ranks; overwrites `out`. Every
    /// local grain must lie inside one of `blockBoxes` if any are given (the blocks of this
    /// rank; they only sharpen the pruning). Returns the total potential energy ½ Σ m φ
    /// over all ranks in J. Throws core::InputError on every rank for bad masses.
    /// COLLECTIVE over the communicator.
    double evaluate(PointMasses const& local, FieldOut out,
                    std::span<core::AABB const> blockBoxes = {});

    [[nodiscard]] TreeStats const& stats() const { return m_stats; }
    [[nodiscard]] TreeOptions const& options() const { return m_options; }

private:
    /// The boxes of every rank: tight boxes of this rank's grains, all-gathered.
    std::vector<std::vector<core::AABB>> gatherBoxes(PointMasses const& local,
                                                     std::span<core::AABB const> blockBoxes);

    core::Comm m_comm;
    TreeOptions m_options;
    core::SparseExchange m_exchange;
    TreeStats m_stats;
};

/// Tight boxes of `grains`: one per box of `blockBoxes` that holds grains (the grains inside
/// it), plus one for grains outside every block box; one box if `blockBoxes` is empty.
/// Not collective.
[[nodiscard]] std::vector<core::AABB> tightBoxes(PointMasses const& grains,
                                                 std::span<core::AABB const> blockBoxes);

} // namespace regolith::gravity::tree
