#include "coupling/balance/BlockWeights.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace regolith::coupling {

namespace {

using BlockKey = std::tuple<double, double, double, int>; // box minimum corner, level

BlockKey keyOf(core::AABB const& box, int level) {
    return {box.min.x(), box.min.y(), box.min.z(), level};
}

} // namespace

double BlockLoadModel::weight(particles::LocalParticles::LeafLoad const& load) const {
    double const cells =
        static_cast<double>(cellsPerBlock[0]) * cellsPerBlock[1] * cellsPerBlock[2];
    return 1.0 + grainWeight * static_cast<double>(load.grains) +
           contactWeight * static_cast<double>(load.contacts) + cellWeight * cells;
}

double directGravityWeight(double grains, double updateEvery) {
    return 1.0 + BlockLoadModel::kDirectPairWeight * grains / std::max(updateEvery, 1.0);
}

double loadImbalance(core::Comm const& comm, double load) {
    double const most = comm.allReduce(load, core::ReduceOp::Max);
    double const total = comm.allReduce(load, core::ReduceOp::Sum);
    return total > 0.0 ? most * comm.size() / total : 1.0;
}

LoadSpread loadSpread(core::Comm const& comm, particles::LocalParticles const& local,
                      BlockLoadModel const& model) {
    std::array<double, 2> most{0.0, 0.0}; // this rank's load, its heaviest block
    for (std::size_t b = 0; b < local.blocks().size(); ++b)
        for (particles::LocalParticles::LeafLoad const& leaf : local.loadPerLeaf(b)) {
            double const w = model.weight(leaf);
            most[0] += w;
            most[1] = std::max(most[1], w);
        }
    double const total = comm.allReduce(most[0], core::ReduceOp::Sum);
    comm.allReduceInPlace(std::span<double>(most), core::ReduceOp::Max);
    if (!(total > 0.0))
        return {};
    double const mean = total / comm.size();
    return {most[0] / mean, std::max(1.0, most[1] / mean)};
}

domain::BlockWeight grainAndCellWeights(core::Comm const& comm,
                                        particles::LocalParticles const& local,
                                        BlockLoadModel const& model) {
    constexpr std::size_t kFields = 5; // min x, y, z, level, weight
    std::vector<double> mine;
    mine.reserve(local.blocks().size() * kFields);
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        auto const loads = local.loadPerLeaf(b);
        auto const& leaves = blocks[b].block->leaves;
        for (std::size_t l = 0; l < leaves.size(); ++l) {
            core::AABB const& box = leaves[l].aabb;
            mine.insert(mine.end(),
                        {box.min.x(), box.min.y(), box.min.z(),
                         static_cast<double>(leaves[l].id.level()), model.weight(loads[l])});
        }
    }
    std::vector<double> const all = comm.allGatherVarying(std::span<double const>(mine));
    auto table = std::make_shared<std::map<BlockKey, double>>();
    for (std::size_t i = 0; i + kFields <= all.size(); i += kFields)
        (*table)[{all[i], all[i + 1], all[i + 2], static_cast<int>(all[i + 3])}] = all[i + 4];
    // A block the table does not know cannot occur for the same specification; weight 1
    // keeps the assignment defined regardless.
    return [table](core::AABB const& box, int level) {
        auto const it = table->find(keyOf(box, level));
        return it == table->end() ? 1.0 : it->second;
    };
}

} // namespace regolith::coupling
