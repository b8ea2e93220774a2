#include "coupling/balance/BlockSplit.hpp"

#include "coupling/balance/CutSurface.hpp"
#include "domain/ForestBuilder.hpp"
#include "domain/SfcPartition.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <vector>

namespace regolith::coupling {

namespace {

/// The largest of `values` (0 if none).
double largest(std::span<double const> values) {
    double most = 0.0;
    for (double const v : values)
        most = std::max(most, v);
    return most;
}

/// The loads of the ranks when the leaves weighing `load` go to the ranks `owner`.
std::vector<double> rankLoads(std::span<double const> load, std::span<int const> owner, int ranks) {
    std::vector<double> out(static_cast<std::size_t>(ranks), 0.0);
    for (std::size_t l = 0; l < load.size(); ++l)
        out[static_cast<std::size_t>(owner[l])] += load[l];
    return out;
}

/// The largest cost (CutSurface.hpp) of the least-largest-load cut of the forest `spec`,
/// whose leaves weigh `load`. COLLECTIVE.
double largestCost(core::Comm const& comm, particles::LocalParticles const& local,
                   particles::ContactCounts const& contacts, BlockLoadModel const& model,
                   domain::ForestSpec const& spec, std::span<double const> load) {
    std::vector<int> const owner = domain::partitionCurve(load, comm.size());
    return largest(
        rankCosts(comm, local, contacts, model, domain::ForestBuilder(spec), load, owner));
}

} // namespace

SplitForest splitHeavyBlocks(core::Comm const& comm, particles::LocalParticles const& local,
                             particles::ContactCounts const& contacts, BlockLoadModel const& model,
                             domain::ForestSpec spec, SplitLimits const& limits) {
    domain::ForestSpec const whole = spec;
    std::size_t firstBlocks = 0;
    std::size_t blocks = 0;
    std::vector<double> wholeLoad, load;
    bool weighSurface = false; // the split is taken only if it costs the busiest rank less
    for (bool first = true;; first = false) {
        domain::ForestBuilder const builder(spec);
        blocks = builder.leaves().size();
        if (first)
            firstBlocks = blocks;
        std::vector<particles::LocalParticles::LeafLoad> const counts =
            leafCounts(comm, local, contacts, builder);
        load.clear();
        for (particles::LocalParticles::LeafLoad const& leaf : counts)
            load.push_back(model.weight(leaf));
        std::vector<double> widest(load.size(), 0.0); // the widest grain centred in each leaf
        forEachMasterInLeaf(
            local, contacts, builder,
            [&](std::size_t leaf, particles::ParticleStorage const& ps, std::size_t i,
                std::uint32_t) { widest[leaf] = std::max(widest[leaf], 2.0 * ps.radius(i)); });
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
        // The first round decides. A block above the floor: no cut of whole blocks reaches it.
        // Lighter blocks: the best cut of them may, else a split may, at the cost of surface.
        if (first && !(largest(load) > limits.floor * mean)) {
            std::vector<int> const owner = domain::partitionCurve(load, comm.size());
            if (!(largest(rankLoads(load, owner, comm.size())) > limits.floor * mean))
                break;
            weighSurface = true;
            wholeLoad = load;
        }
        if (split.empty())
            break;
        spec.refine.insert(spec.refine.end(), split.begin(), split.end());
    }
    if (weighSurface && blocks > firstBlocks &&
        !(largestCost(comm, local, contacts, model, spec, load) <
          largestCost(comm, local, contacts, model, whole, wholeLoad)))
        return {whole, 0};
    return {std::move(spec), (blocks - firstBlocks) / 7}; // each split adds seven leaves
}

} // namespace regolith::coupling
