#include "apps/regolith/BlockPlacement.hpp"

#include "coupling/balance/BlockWeights.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/RestoreGrains.hpp"

#include <algorithm>
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

} // namespace

BlockPlacement uniformPlacement(core::Comm const& comm, SceneDescription const& scene) {
    BlockPlacement p;
    p.forest = std::make_unique<domain::BlockForest>(comm, scene.forest);
    p.particleForest = std::make_unique<domain::BlockForest>(
        comm, scene.forest, domain::BlockWeight{}, scene.sync.subdomains);
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
    domain::BlockWeight const weight = coupling::grainAndCellWeights(comm, *placement.local, model);
    auto forest = std::make_unique<domain::BlockForest>(comm, scene.forest, weight);
    if (comm.allTrue(sameBlocks(*forest, *placement.forest)))
        return false;
    auto particleForest =
        std::make_unique<domain::BlockForest>(comm, scene.forest, weight, scene.sync.subdomains);
    auto local = std::make_unique<particles::LocalParticles>(*particleForest);
    {
        // The masters travel as a restart's grains do (one sparse exchange, state complete).
        std::vector<io::GrainState> const grains = io::collectMasters(*placement.local);
        placement.local.reset();
        io::restoreGrains(comm, *local, grains, "balancing the blocks by load");
    }
    placement.local = std::move(local);
    placement.particleForest = std::move(particleForest);
    placement.forest = std::move(forest);
    return true;
}

} // namespace regolith::apps
