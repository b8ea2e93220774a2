#include "coupling/balance/BlockWeights.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <span>
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
                      particles::ContactCounts const& contacts, BlockLoadModel const& model) {
    local.requireCountsCover(contacts);
    std::array<double, 2> most{0.0, 0.0}; // this rank's load, its heaviest block
    for (std::size_t b = 0; b < local.blocks().size(); ++b)
        for (particles::LocalParticles::LeafLoad const& leaf : local.loadPerLeaf(b, contacts[b])) {
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

std::vector<particles::LocalParticles::LeafLoad>
leafCounts(core::Comm const& comm, particles::LocalParticles const& local,
           particles::ContactCounts const& contacts, domain::ForestBuilder const& builder) {
    std::size_t const leaves = builder.leaves().size();
    std::vector<double> counts(2 * leaves, 0.0); // grains, contacts per leaf: exact sums
    forEachMasterInLeaf(local, contacts, builder,
                        [&](std::size_t leaf, particles::ParticleStorage const&, std::size_t,
                            std::uint32_t contactsOfGrain) {
                            counts[2 * leaf] += 1.0;
                            counts[2 * leaf + 1] += static_cast<double>(contactsOfGrain);
                        });
    comm.allReduceInPlace(std::span<double>(counts), core::ReduceOp::Sum);
    std::vector<particles::LocalParticles::LeafLoad> out(leaves);
    for (std::size_t l = 0; l < leaves; ++l)
        out[l] = {static_cast<std::size_t>(counts[2 * l]),
                  static_cast<std::size_t>(counts[2 * l + 1])};
    return out;
}

std::vector<double> leafLoads(core::Comm const& comm, particles::LocalParticles const& local,
                              particles::ContactCounts const& contacts, BlockLoadModel const& model,
                              domain::ForestBuilder const& builder) {
    std::vector<double> load;
    for (particles::LocalParticles::LeafLoad const& leaf :
         leafCounts(comm, local, contacts, builder))
        load.push_back(model.weight(leaf));
    return load;
}

domain::BlockWeight grainAndCellWeights(core::Comm const& comm,
                                        particles::LocalParticles const& local,
                                        particles::ContactCounts const& contacts,
                                        BlockLoadModel const& model,
                                        domain::ForestSpec const& spec) {
    domain::ForestBuilder const builder(spec);
    std::vector<double> const load = leafLoads(comm, local, contacts, model, builder);
    auto table = std::make_shared<std::map<BlockKey, double>>();
    for (std::size_t l = 0; l < load.size(); ++l) {
        domain::ForestLeaf const& leaf = builder.leaves()[l];
        (*table)[keyOf(builder.geometry().box(leaf.box), leaf.id.level())] = load[l];
    }
    // A block the table does not know cannot occur for the same specification; weight 1
    // keeps the assignment defined regardless.
    return [table](core::AABB const& box, int level) {
        auto const it = table->find(keyOf(box, level));
        return it == table->end() ? 1.0 : it->second;
    };
}

} // namespace regolith::coupling
