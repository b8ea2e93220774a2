#include "coupling/balance/CutSurface.hpp"

#include "domain/RankBoxes.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

namespace regolith::coupling {

namespace {

/// The 26 unit directions from a cube's centre to its faces, edges and corners.
std::array<core::Vec3, 26> surfaceDirections() {
    std::array<core::Vec3, 26> out{};
    std::size_t n = 0;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x != 0 || y != 0 || z != 0)
                    out[n++] = core::Vec3(x, y, z).normalized();
    return out;
}

} // namespace

std::vector<double> rankCosts(core::Comm const& comm, particles::LocalParticles const& local,
                              particles::ContactCounts const& contacts, BlockLoadModel const& model,
                              domain::ForestBuilder const& builder, std::span<double const> load,
                              std::span<int const> owner) {
    // The cuboids the synchronisation would cross: each rank's leaves merged.
    std::vector<domain::ForestLeaf> leaves = builder.leaves();
    for (std::size_t l = 0; l < leaves.size(); ++l)
        leaves[l].owner = owner[l];
    domain::SubdomainCut const cut = domain::mergeRankLeaves(leaves);
    std::vector<std::uint32_t> boxOf(leaves.size(), 0);
    for (std::uint32_t b = 0; b < cut.boxes.size(); ++b)
        for (std::uint32_t const l : cut.leavesOf(cut.boxes[b]))
            boxOf[l] = b;

    static std::array<core::Vec3, 26> const directions = surfaceDirections();
    std::vector<double> cost(static_cast<std::size_t>(comm.size()), 0.0);
    std::vector<std::uint32_t> reached; // the other cuboids one grain reaches
    forEachMasterInLeaf(local, contacts, builder,
                        [&](std::size_t leaf, particles::ParticleStorage const& ps, std::size_t i,
                            std::uint32_t contactsOfGrain) {
                            reached.clear();
                            for (core::Vec3 const& u : directions) {
                                auto const at =
                                    builder.geometry().locate(ps.position(i) + ps.radius(i) * u);
                                if (!at)
                                    continue;
                                std::uint32_t const b = boxOf[builder.leafAt(at->cell)];
                                if (b != boxOf[leaf] &&
                                    std::find(reached.begin(), reached.end(), b) == reached.end())
                                    reached.push_back(b);
                            }
                            double const shadow =
                                1.0 + model.contactWeight * static_cast<double>(contactsOfGrain);
                            for (std::uint32_t const b : reached)
                                cost[static_cast<std::size_t>(cut.boxes[b].owner)] += shadow;
                        });
    comm.allReduceInPlace(std::span<double>(cost), core::ReduceOp::Sum);
    for (std::size_t l = 0; l < load.size(); ++l)
        cost[static_cast<std::size_t>(owner[l])] += load[l];
    return cost;
}

} // namespace regolith::coupling
