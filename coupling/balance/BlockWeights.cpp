#include "coupling/balance/BlockWeights.hpp"

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

domain::BlockWeight grainAndCellWeights(core::Comm const& comm,
                                        particles::LocalParticles const& local,
                                        BlockLoadModel const& model) {
    double const cells = static_cast<double>(model.cellsPerBlock[0]) * model.cellsPerBlock[1] *
                         model.cellsPerBlock[2];
    constexpr std::size_t kFields = 5; // min x, y, z, level, weight
    std::vector<double> mine;
    mine.reserve(local.blocks().size() * kFields);
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        std::vector<std::size_t> const grains = local.countMastersPerLeaf(b);
        auto const& leaves = blocks[b].block->leaves;
        for (std::size_t l = 0; l < leaves.size(); ++l) {
            core::AABB const& box = leaves[l].aabb;
            mine.insert(mine.end(),
                        {box.min.x(), box.min.y(), box.min.z(),
                         static_cast<double>(leaves[l].id.level()),
                         1.0 + static_cast<double>(grains[l]) + model.cellWeight * cells});
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
