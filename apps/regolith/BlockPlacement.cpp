#include "apps/regolith/BlockPlacement.hpp"

#include "coupling/balance/BlockSplit.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "domain/SpecValidation.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/checkpoint/RestoreGrains.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace regolith::apps {

namespace {

bool usesGrid(std::string const& method) {
    coupling::GravityMethodEntry const* entry = coupling::findGravityMethod(method);
    return entry && entry->usesGrid;
}

bool sameBlocks(domain::BlockForest const& a, domain::BlockForest const& b) {
    return std::equal(a.blocks().begin(), a.blocks().end(), b.blocks().begin(), b.blocks().end(),
                      [](domain::Block const& x, domain::Block const& y) { return x.id == y.id; });
}

} // namespace

coupling::Placement uniformPlacement(core::Comm const& comm, SceneDescription const& scene) {
    return coupling::placeBlocks(comm, scene.forest, {}, scene.sync.subdomains);
}

coupling::BlockLoadModel loadModel(core::Comm const& comm, SceneDescription const& scene,
                                   particles::LocalParticles const& local) {
    coupling::BlockLoadModel model;
    GravitySection const& g = scene.gravity;
    if (usesGrid(g.self))
        model = {scene.forest.cellsPerBlock, scene.forest.cellWeight};
    // The direct sum's work is known when its updates keep a fixed schedule.
    bool const fixedSchedule = g.updateThreshold <= 0.0 && !g.updateEveryAdaptive;
    if (g.self == "direct" && fixedSchedule) { // the registered name of gravity/direct
        auto const grains =
            comm.allReduce(static_cast<double>(local.countMasters()), core::ReduceOp::Sum);
        model.grainWeight =
            coupling::directGravityWeight(grains, static_cast<double>(g.updateEvery));
    }
    return model;
}

namespace {

/// How far the blocks of `scene` may split: balance.split_levels below its deepest blocks.
coupling::SplitLimits splitLimits(SceneDescription const& scene) {
    coupling::SplitLimits limits;
    // Whole blocks that cannot reach the imbalance the hysteresis asks of a new cut
    // (DynamicBalance.hpp), and a finer split than the threshold needs, so that the cut lasts
    // while the load keeps gathering.
    limits.floor = 1.0 + 0.5 * (scene.balance.threshold - 1.0);
    limits.share = splitShare(scene.balance.threshold);
    int deepest = 0;
    for (domain::RefineRegion const& r : scene.forest.refine)
        deepest = std::max(deepest, r.level);
    limits.deepestLevel =
        std::min(deepest + static_cast<int>(scene.balance.splitLevels), domain::kMaxRefineLevel);
    return limits;
}

} // namespace

bool balanceByLoad(core::Comm const& comm, SceneDescription const& scene,
                   coupling::Placement& placement, particles::ContactCounts const& contacts,
                   WorthMoving const& worthMoving) {
    if (scene.forest.balance == domain::ForestSpec::Balance::Blocks)
        return false;
    coupling::BlockLoadModel const model = loadModel(comm, scene, *placement.local);
    domain::ForestSpec spec = placement.spec;
    if (scene.balance.splitLevels > 0)
        spec = coupling::splitHeavyBlocks(comm, *placement.local, contacts, model, std::move(spec),
                                          splitLimits(scene))
                   .spec;
    domain::BlockWeight const weight =
        coupling::grainAndCellWeights(comm, *placement.local, contacts, model, spec);
    coupling::Placement balanced = coupling::placeBlocks(comm, spec, weight, scene.sync.subdomains);
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
    placement.spec = std::move(balanced.spec);
    *placement.forest = std::move(*balanced.forest);
    *placement.particleForest = std::move(*balanced.particleForest);
    *placement.local = particles::LocalParticles(*placement.particleForest);
    io::restoreGrains(comm, *placement.local, grains, "balancing the blocks by load");
    return true;
}

} // namespace regolith::apps
