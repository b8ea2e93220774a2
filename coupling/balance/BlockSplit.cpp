#include "coupling/balance/BlockSplit.hpp"

#include "domain/ForestBuilder.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <vector>

namespace regolith::coupling {

SplitForest splitHeavyBlocks(core::Comm const& comm, particles::LocalParticles const& local,
                             BlockLoadModel const& model, domain::ForestSpec spec,
                             SplitLimits const& limits) {
    std::size_t firstBlocks = 0;
    std::size_t blocks = 0;
    for (bool first = true;; first = false) {
        domain::ForestBuilder const builder(spec);
        blocks = builder.leaves().size();
        if (first)
            firstBlocks = blocks;
        std::vector<particles::LocalParticles::LeafLoad> const counts =
            leafCounts(comm, local, builder);
        std::vector<double> load;
        for (particles::LocalParticles::LeafLoad const& leaf : counts)
            load.push_back(model.weight(leaf));
        std::vector<double> widest(load.size(), 0.0); // the widest grain centred in each leaf
        forEachMasterInLeaf(
            local, builder,
            [&](std::size_t leaf, particles::ParticleStorage const& ps, std::size_t i) {
                widest[leaf] = std::max(widest[leaf], 2.0 * ps.radius(i));
            });
        comm.allReduceInPlace(std::span<double>(widest), core::ReduceOp::Max);
        double const mean = std::accumulate(load.begin(), load.end(), 0.0) / comm.size();
        std::vector<domain::RefineRegion> split;
        for (std::size_t l = 0; l < load.size(); ++l) {
            domain::ForestLeaf const& leaf = builder.leaves()[l];
            core::AABB const box = builder.geometry().box(leaf.box);
            if (!(load[l] > limits.share * mean) || counts[l].grains < 2 ||
                leaf.id.level() >= limits.deepestLevel || 0.5 * box.minEdge() < widest[l])
                continue;
            // A region inside the block only (its middle half), refined to the next level.
            core::Vec3 const quarter = 0.25 * box.extent();
            split.push_back({{box.min + quarter, box.max - quarter}, leaf.id.level() + 1});
        }
        // The first round decides: with no block above the floor, whole blocks even the loads.
        bool const floorReached =
            !first || *std::max_element(load.begin(), load.end()) > limits.floor * mean;
        if (split.empty() || !floorReached)
            break;
        spec.refine.insert(spec.refine.end(), split.begin(), split.end());
    }
    return {std::move(spec), (blocks - firstBlocks) / 7}; // each split adds seven leaves
}

} // namespace regolith::coupling
