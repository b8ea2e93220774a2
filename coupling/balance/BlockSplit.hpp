#pragma once
/// Blocks that split during a run where the load gathers. A cut of whole blocks along the
/// curve comes within one block's weight of the mean load (domain/SfcPartition.hpp), so no cut
/// evens the ranks while one block holds a large part of a rank's share (the block floor,
/// docs/balance.md): a cold cloud collapsing into one block, a pile settling into a few. Where
/// the best cut of whole blocks misses `floor`, every block heavier than `share` is refined
/// into its eight children, by a refine region added to the run's forest specification, round
/// after round until no block is heavier than `share` of a rank's mean load or the limits stop
/// it. With share <= threshold - 1 the cut that follows reaches the threshold. Splits are not
/// free: a rank's region follows the finer blocks, so its surface and the shadows on it grow
/// (CutSurface.hpp). Where one block alone outweighs `floor` shares no cut of whole blocks
/// reaches it, and the blocks split; where the blocks are lighter, the split is taken only if
/// its cut costs the busiest rank less than the whole blocks' cut, shadows counted: so where
/// the grains' own work is large against their contacts' (a direct self-gravity sum) the
/// blocks split, and a DEM pile whose cut misses `floor` by a little keeps its blocks.
/// Blocks are not merged back.
#include "coupling/balance/BlockWeights.hpp"
#include "domain/ForestSpec.hpp"

#include <cstddef>

namespace regolith::coupling {

/// How far blocks may split (balance.split_levels). Nor does a block split into children
/// narrower than the widest grain centred in it (its grains stay in the next-neighbour class
/// of the first paper's synchronisation), or when it holds one grain (its children would
/// weigh as much).
struct SplitLimits {
    /// Nothing splits unless the best cut of whole blocks has a rank above this times the
    /// mean load (a block above it: no such cut goes below; see the file comment).
    double floor = 1.05;
    double share = 0.05;  ///< then every block heavier than share x a rank's mean load splits
    int deepestLevel = 0; ///< no block is split below this level
};

/// The specification with the refine regions that split the heavy blocks, and how many
/// blocks were split (each into eight; those 2:1 balance splits included).
struct SplitForest {
    domain::ForestSpec spec;
    std::size_t splits = 0;
};

/// `spec` with its heavy blocks split, by the loads of `local`'s masters (see the file
/// comment). The same on every rank. COLLECTIVE (two all-reductions per round, one more for
/// each cut whose cost is weighed).
[[nodiscard]] SplitForest splitHeavyBlocks(core::Comm const& comm,
                                           particles::LocalParticles const& local,
                                           particles::ContactCounts const& contacts,
                                           BlockLoadModel const& model, domain::ForestSpec spec,
                                           SplitLimits const& limits);

} // namespace regolith::coupling
