// The generic scene run behind `regolith` and the reference-scene apps: builds the block
// forest, generates the initial particles on every rank, runs the DEM time steps with shadow
// synchronisation and writes the run summary and dump (DESIGN.md, "Contracts").
#include "apps/regolith/SceneRun.hpp"

#include "apps/common/ConservedQuantities.hpp"
#include "apps/common/OutputFile.hpp"
#include "apps/common/RunSummary.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/common/StateDump.hpp"
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/GravitySetup.hpp"
#include "apps/regolith/InitialState.hpp"
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/SceneReport.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/regolith/TimeLoop.hpp"
#include "apps/scenarios/Scenarios.hpp"
#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <string>

namespace regolith::apps {

int runScene(core::AppContext& ctx) {
    core::Comm const& world = ctx.world;
    expandScenarios(ctx.scene, world.size());
    SceneDescription scene = parseScene(ctx.scene, ctx.options.scenePath);
    if (!ctx.options.restartPath.empty())
        throw core::InputError(fmt::format("--restart {}: restarting from a checkpoint needs the "
                                           "HDF5 checkpoint reader of the io module, which this "
                                           "build does not have yet",
                                           ctx.options.restartPath));
    // Fail before the run, not after it, if an output file cannot be written.
    if (!ctx.options.jsonPath.empty())
        checkWritable(world, ctx.options.jsonPath, "--json");
    if (!ctx.options.dumpPath.empty())
        checkWritable(world, ctx.options.dumpPath, "--dump");

    domain::BlockForest const forest(world, scene.forest);
    auto const grains = generateLocalGrains(world, ctx.scene, scene, forest);
    std::vector<AutoChoice> choices;
    {
        auto const masters = makeMasters(grains, forest, world.rank());
        choices = resolveAutoChoices(world, masters, scene);
        checkInitialState(world, masters, scene);
        warnLazyUpdateThreshold(world, masters, scene);
    }
    if (ctx.isRoot() && !ctx.options.quiet)
        for (AutoChoice const& c : choices)
            fmt::print("  auto: {} = {} ({})\n", c.key, c.value, c.reason);
    auto const selfGravity = makeSelfGravity(world, forest, scene);
    auto const counts = countParticles(world, static_cast<std::int64_t>(grains.size()));
    if (ctx.isRoot() && !ctx.options.quiet)
        printSceneReport(ctx, scene, forest, counts);
    if (forest.idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        forest.idleRankCount(), world.size());
    auto const wallOverlaps = world.allReduce(
        static_cast<long long>(countWallOverlaps(toMasterRecords(grains), scene.walls)),
        core::ReduceOp::Sum);
    if (wallOverlaps > 0)
        core::log::warn("{} of {} grains overlap a wall at the start", wallOverlaps, counts.total);

    // The particles of this rank's blocks, their shadows, and the time step (DESIGN.md, "The
    // time step"): NNS refuses a grain too large for it (InputError, exit 2 on every rank),
    // then every shadow is created and the initial forces computed.
    particles::LocalParticles local(forest);
    addMasters(local, grains);
    particles::ParticleSync sync(world, forest, scene.sync);
    core::TimerTree timers([] { return MPI_Wtime(); });
    particles::DemStepConfig stepConfig;
    stepConfig.dt = scene.time.dt;
    stepConfig.gravity = scene.gravity.external;
    particles::DemStep dem(world, sync, local, makeContactModel(scene), makeIntegrator(scene),
                           makeWalls(scene), stepConfig, timers);
    // Self-gravity as the step's body forces (after contacts and their reduction).
    if (selfGravity)
        dem.setBodyForces(
            [g = selfGravity.get()](particles::LocalParticles& l) { g->addForces(l); });
    dem.setUp();
    checkOverlapsAcrossBlocks(world, local, dem.contacts(), scene.contact.initialOverlap);

    LoopOutcome const loop = runTimeLoop(world, dem, sync, timers, scene.time.steps);

    auto const masters = masterRecords(local);
    if (!ctx.options.dumpPath.empty())
        writeFileOnRoot(world, ctx.options.dumpPath, gatherDumpCsv(world, masters));

    RunSummary summary;
    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(forest.globalBlockCount());
    summary.sync = std::string(toString(scene.sync.method));
    fillLoopSummary(world, loop, local, summary);
    summary.peakRssBytes = peakRssBytes(world);
    summary.conserved = conservedQuantities(world, masters, scene.gravity.external);
    summary.gravity.method = std::string(toString(scene.gravity.self));
    for (AutoChoice const& c : choices)
        summary.autoChoices.push_back({c.key, c.value, c.reason});
    if (selfGravity) {
        // ½ Σ m φ of the last field computed: the final positions' when it is updated every
        // step (update_threshold = 0).
        summary.conserved.potentialEnergy += selfGravity->stats().potentialEnergy;
        summary.gravity.updates = selfGravity->stats().evaluations;
    }
    summary.checksum = stateChecksum(world, masters);
    if (ctx.isRoot() && !ctx.options.quiet)
        printRunReport(summary, loop.leftDomain, loop.timers);
    if (!ctx.options.jsonPath.empty())
        writeFileOnRoot(world, ctx.options.jsonPath, toJson(summary));
    return 0;
}

} // namespace regolith::apps
