#include "apps/regolith/BlockPlacement.hpp"

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

coupling::BlockLoadModel loadModel(SceneDescription const& scene) {
    coupling::BlockLoadModel model;
    if (usesGrid(scene.gravity.self))
        model = {scene.forest.cellsPerBlock, scene.forest.cellWeight};
    return model;
}

bool balanceByLoad(core::Comm const& comm, SceneDescription const& scene, BlockPlacement& placement,
                   WorthMoving const& worthMoving) {
    if (scene.forest.balance == domain::ForestSpec::Balance::Blocks)
        return false;
    domain::BlockWeight const weight =
        coupling::grainAndCellWeights(comm, *placement.local, loadModel(scene));
    BlockPlacement balanced;
    placeForests(comm, scene, weight, balanced);
    if (comm.allTrue(sameBlocks(*balanced.forest, *placement.forest)))
        return false;
    if (worthMoving) {
        double load = 0.0;
        for (domain::Block const& b : balanced.forest->blocks())
            load += weight(b.aabb, b.id.level());
        if (!worthMoving(coupling::loadImbalance(comm, load)))
            return false;
    }
    // The masters travel as a restart's grains do (one sparse exchange, state complete). The
    // objects stay where they are: what refers to them sees the new assignment.
    std::vector<io::GrainState> const grains = io::collectMasters(*placement.local);
    *placement.forest = std::move(*balanced.forest);
    *placement.particleForest = std::move(*balanced.particleForest);
    *placement.local = particles::LocalParticles(*placement.particleForest);
    io::restoreGrains(comm, *placement.local, grains, "balancing the blocks by load");
    return true;
}

} // namespace regolith::apps
