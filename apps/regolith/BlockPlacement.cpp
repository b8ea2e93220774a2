#include "apps/regolith/BlockPlacement.hpp"

#include "coupling/balance/BlockWeights.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/RestoreGrains.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace regolith::apps {

namespace {

bool usesGrid(SelfGravity method) {
    return method == SelfGravity::Pm || method == SelfGravity::P3m;
}

bool sameBlocks(domain::BlockForest const& a, domain::BlockForest const& b) {
    return std::equal(a.blocks().begin(), a.blocks().end(), b.blocks().begin(), b.blocks().end(),
                      [](domain::Block const& x, domain::Block const& y) { return x.id == y.id; });
}

/// The forest and the particles' cut of it, for block weights `weight`.
void placeForests(core::Comm const& comm, SceneDescription const& scene,
                  domain::BlockWeight const& weight, BlockPlacement& p) {
    auto [blocks, subdomains] =
        domain::BlockForest::blocksAnd(comm, scene.forest, weight, scene.sync.subdomains);
    p.forest = std::make_unique<domain::BlockForest>(std::move(blocks));
    p.particleForest = std::make_unique<domain::BlockForest>(std::move(subdomains));
}

} // namespace

BlockPlacement uniformPlacement(core::Comm const& comm, SceneDescription const& scene) {
    BlockPlacement p;
    placeForests(comm, scene, {}, p);
    p.local = std::make_unique<particles::LocalParticles>(*p.particleForest);
    return p;
}

bool balanceByLoad(core::Comm const& comm, SceneDescription const& scene,
                   BlockPlacement& placement) {
    if (scene.forest.balance == domain::ForestSpec::Balance::Blocks)
        return false;
    coupling::BlockLoadModel model;
    if (usesGrid(scene.gravity.self))
        model = {scene.forest.cellsPerBlock, scene.forest.cellWeight};
    BlockPlacement balanced;
    placeForests(comm, scene, coupling::grainAndCellWeights(comm, *placement.local, model),
                 balanced);
    if (comm.allTrue(sameBlocks(*balanced.forest, *placement.forest)))
        return false;
    auto local = std::make_unique<particles::LocalParticles>(*balanced.particleForest);
    {
        // The masters travel as a restart's grains do (one sparse exchange, state complete).
        std::vector<io::GrainState> const grains = io::collectMasters(*placement.local);
        placement.local.reset();
        io::restoreGrains(comm, *local, grains, "balancing the blocks by load");
    }
    placement.local = std::move(local);
    placement.particleForest = std::move(balanced.particleForest);
    placement.forest = std::move(balanced.forest);
    return true;
}

} // namespace regolith::apps
