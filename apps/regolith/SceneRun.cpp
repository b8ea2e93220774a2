// The generic scene run behind `regolith` and the apps built on it: reads the scene, generates
// the grains on every rank (or restores a checkpoint's, --restart), runs them as a
// coupling::Simulation with the scene's outputs as its observers (RunOutputs) and writes the run
// summary and dump (docs/design.md, "Contracts").
#include "apps/regolith/SceneRun.hpp"

#include "apps/common/ConservedQuantities.hpp"
#include "apps/common/OutputDirLock.hpp"
#include "apps/common/OutputFile.hpp"
#include "apps/common/RunSummary.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/common/StateDump.hpp"
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/BalanceChoices.hpp"
#include "apps/regolith/BlockPlacement.hpp"
#include "apps/regolith/Checkpointing.hpp"
#include "apps/regolith/GravitySetup.hpp"
#include "apps/regolith/GridAccuracy.hpp"
#include "apps/regolith/InitialState.hpp"
#include "apps/regolith/LoopSummary.hpp"
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/RunOutputs.hpp"
#include "apps/regolith/RunPaths.hpp"
#include "apps/regolith/SceneKeyLocation.hpp"
#include "apps/regolith/SceneReport.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/regolith/SpeedChoices.hpp"
#include "apps/regolith/WallLoads.hpp"
#include "apps/scenarios/Scenarios.hpp"
#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "domain/BlockForest.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace regolith::apps {

namespace {

/// The masters of a new run: the scene's [[particles]], with the scene's "auto" keys resolved
/// from them (returned), checked. COLLECTIVE.
std::vector<AutoChoice> generateInitialState(core::AppContext const& ctx, SceneDescription& scene,
                                             domain::BlockForest const& forest,
                                             particles::LocalParticles& local) {
    auto masters = generateLocalMasters(ctx.world, ctx.scene, scene, forest);
    std::vector<AutoChoice> const choices = resolveAutoChoices(ctx.world, masters, scene);
    checkInitialState(ctx.world, masters, scene);
    checkGridAccuracy(ctx.world, masters, scene);
    local.adoptMasters(std::move(masters));
    warnSelfGravityParameters(ctx.world, local, scene);
    return choices;
}

/// contact.neighbour_skin, if given, below the smallest block edge: a sanity bound, as a skin
/// of a block edge already lists pairs across most of a block (memory growing with the square
/// of its grains) and one of its diagonal every pair. InputError on every rank otherwise.
/// COLLECTIVE.
void requireSkinBelowBlockEdges(core::Comm const& world, domain::BlockForest const& forest,
                                std::optional<double> skin) {
    if (!skin)
        return;
    double edge = std::numeric_limits<double>::infinity();
    for (domain::Block const& b : forest.blocks())
        edge = std::min(edge, b.aabb.minEdge());
    edge = world.allReduce(edge, core::ReduceOp::Min);
    if (!(*skin < edge))
        throw core::InputError(fmt::format("contact.neighbour_skin = {}: expected a length below "
                                           "the smallest block edge, {}",
                                           *skin, edge));
}

/// The scene read and checked, and its grains on their ranks: a new run's generated, a
/// restart's restored with the "auto" choices of the run that wrote the checkpoint.
struct PreparedRun {
    SceneDescription scene;
    coupling::Placement placement;
    std::vector<AutoChoice> choices;
    std::string text; ///< the scene as stored in checkpoints (sceneText, withAutoChoices)
    RunStart start;
    std::string summaryFile;
    OutputDirLock outputLock; ///< held from the checks of the paths to the run's end
};

/// COLLECTIVE.
PreparedRun prepareRun(core::AppContext& ctx) {
    core::Comm const& world = ctx.world;
    expandScenarios(ctx.scene, world.size());
    PreparedRun run;
    run.scene = parseScene(ctx.scene, ctx.options.scenePath);
    SceneDescription& scene = run.scene;
    // Fail before the run, not after it, if an output file would overwrite an input or
    // another output, or cannot be written.
    checkRunPaths(world, ctx.options, scene);
    if (writesIntoOutputDir(ctx.options, scene))
        run.outputLock = OutputDirLock(world, scene.output.dir);
    run.summaryFile = summaryPath(ctx.options, scene);
    checkWritable(world, run.summaryFile,
                  ctx.options.jsonPath.empty() ? "the run summary" : "--json");
    if (!ctx.options.dumpPath.empty())
        checkWritable(world, ctx.options.dumpPath, "--dump");

    // The grains are placed on equally weighted blocks, then the blocks are re-assigned by
    // their load.
    AutoChoice rootBlocks = resolveRootBlocks(world, scene);
    run.placement = uniformPlacement(world, scene);
    // Before any grain is made: the blocks' geometry is final here (balancing moves owners).
    requireSkinBelowBlockEdges(world, *run.placement.forest, scene.contact.neighbourSkin);
    run.text = sceneText(ctx); // stored in checkpoints, compared on a restart
    if (!ctx.options.restartPath.empty()) {
        // "auto" takes what the checkpoint's run chose, before the checkpoint's dt is compared.
        double const started = MPI_Wtime();
        io::CheckpointSlice slice = io::readCheckpoint(world, ctx.options.restartPath);
        requireSameDomain(ctx.options.restartPath, slice.info, scene); // the first question
        run.choices = reuseAutoChoices(ctx, scene, slice.info.scene);
        run.text = withAutoChoices(std::move(run.text), run.choices);
        run.start =
            restoreState(ctx, scene, run.text, std::move(slice), started, *run.placement.local);
    } else {
        run.choices =
            generateInitialState(ctx, scene, *run.placement.particleForest, *run.placement.local);
        run.text = withAutoChoices(std::move(run.text), run.choices);
    }
    // Not in the checkpoint's scene text: they change the speed, not the trajectory.
    if (!rootBlocks.key.empty())
        run.choices.push_back(std::move(rootBlocks));
    for (AutoChoice& c : resolveBalanceChoices(world, scene))
        run.choices.push_back(std::move(c));
    balanceByLoad(world, scene, run.placement,
                  run.placement.local->contactsStamped(static_cast<std::uint32_t>(run.start.step)));
    for (AutoChoice& c : resolveSpeedChoices(world, *run.placement.local, scene))
        run.choices.push_back(std::move(c));
    if (ctx.isRoot() && !ctx.options.quiet)
        for (AutoChoice const& c : run.choices)
            fmt::print("  auto: {} = {} ({})\n", c.key, c.value, c.reason);
    return run;
}

/// The coupled run of `scene`: its forest, synchronisation, contact law, integrator, walls
/// and self-gravity.
coupling::SimulationSetup simulationSetup(SceneDescription const& scene) {
    coupling::SimulationSetup setup;
    setup.domain = scene.forest;
    setup.subdomains = scene.sync.subdomains;
    setup.sync = scene.sync;
    setup.dem.dt = scene.time.dt;
    setup.dem.gravity = scene.gravity.external;
    if (scene.contact.neighbourSkin) { // else DemStep's default, relative to the radius
        setup.dem.detector.skin = *scene.contact.neighbourSkin;
        setup.dem.detector.relativeSkin = 0.0;
    }
    setup.contact = makeContactModel(scene);
    setup.allowUnstable = scene.time.allowUnstable;
    setup.integrator = makeIntegrator(scene);
    setup.walls = makeWalls(scene);
    setup.selfGravity = selfGravityConfig(scene);
    return setup;
}

/// Prints the scene report and warns about idle ranks and grains in walls, then starts the
/// run (docs/design.md, "The time step"): NNS refuses a grain too large for it (InputError,
/// exit 2 on every rank), then every shadow is created and, for a new run, the initial forces
/// computed (a restart has them from the checkpoint). COLLECTIVE.
void startRun(core::AppContext const& ctx, PreparedRun& run, coupling::Simulation& sim,
              ParticleCounts const& counts) {
    core::Comm const& world = ctx.world;
    SceneDescription const& scene = run.scene;
    if (ctx.isRoot() && !ctx.options.quiet)
        printSceneReport(ctx, scene, sim.forest(),
                         sim.placement().particleForest->globalSubdomainCount(), counts,
                         run.start.step);
    if (sim.forest().idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        sim.forest().idleRankCount(), world.size());
    bool const restart = run.start.checkpoint.has_value();
    auto const wallOverlaps = world.allReduce(
        static_cast<long long>(countWallOverlaps(masterSource(sim.grains()), scene.walls)),
        core::ReduceOp::Sum);
    if (wallOverlaps > 0 && !restart)
        core::log::warn("{} of {} grains overlap a wall at the start", wallOverlaps, counts.total);
    if (restart) {
        sim.resume(run.start.step, run.start.time);
        if (coupling::SelfGravityForces* g = sim.selfGravity()) {
            restoreSelfGravity(*run.start.checkpoint, *g); // cached field, update policy
            if (scene.output.vtkEvery > 0) // the restart step's grid output, like every other's
                g->refreshGridFields(sim.grains());
        }
        run.start.checkpoint.reset(); // the grains are in the simulation now
    } else {
        sim.start();
        checkOverlapsAcrossBlocks(world, sim.grains(), sim.dem().contacts(),
                                  scene.contact.initialOverlap);
        if (sim.selfGravity()) // the first field's error, on this scene's grains
            checkMeasuredGridAccuracy(*sim.selfGravity(), scene);
    }
}

/// The conserved quantities now, self-gravity's potential energy that of its last field.
/// COLLECTIVE.
RunSummary::Conserved conservedNow(coupling::Simulation const& sim, SceneDescription const& scene) {
    RunSummary::Conserved c =
        conservedQuantitiesFrom(sim.comm(), masterSource(sim.grains()), scene.gravity.external);
    if (sim.selfGravity())
        c.potentialEnergy += sim.selfGravity()->stats().potentialEnergy;
    return c;
}

/// The run summary's self-gravity keys, and the warning when its measured error is too large.
void summariseSelfGravity(coupling::SelfGravityForces const& g, SceneDescription const& scene,
                          RunSummary& summary) {
    summary.gravity.updates = g.stats().evaluations;
    summary.gravity.interval = g.updateInterval();
    coupling::ForceErrorMonitor const& measured = g.measuredError();
    summary.gravity.checks = measured.checks();
    summary.gravity.samples = measured.stats().count;
    summary.gravity.medianError = measured.stats().median;
    summary.gravity.p99Error = measured.stats().p99;
    summary.gravity.maxError = measured.stats().max;
    std::string const warning =
        measuredErrorWarning(measured, scene, g.stats().evaluations, g.stats().steps);
    if (!warning.empty())
        core::log::warn("{}", warning);
}

/// Writes --dump and the run summary (both tried, then every failure reported: a dump that
/// cannot be written does not cost the summary). COLLECTIVE.
void writeRunOutcome(core::AppContext const& ctx, PreparedRun const& run, coupling::Simulation& sim,
                     coupling::RunStats const& stats, RunSummary summary) {
    core::Comm const& world = ctx.world;
    SceneDescription const& scene = run.scene;
    sim.dem().releaseWorkspace(); // the detectors' memory, before the summary below
    // The summary reads the masters from the storages (no record list of every grain: that
    // was the run's memory peak); only --dump gathers them, and frees them again at once.
    MasterSource const masters = masterSource(sim.grains());
    std::string outputFailures;
    auto const tryWrite = [&](std::string const& path, auto const& textOf) {
        try {
            writeFileOnRoot(world, path, textOf());
        } catch (core::InputError const& e) {
            outputFailures += (outputFailures.empty() ? "" : "\n") + std::string(e.what());
        }
    };
    if (!ctx.options.dumpPath.empty())
        tryWrite(ctx.options.dumpPath,
                 [&] { return gatherDumpCsv(world, masterRecords(sim.grains())); });

    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(sim.forest().globalBlockCount());
    summary.particleSubdomains =
        static_cast<std::int64_t>(sim.placement().particleForest->globalSubdomainCount());
    summary.subdomains =
        scene.sync.subdomains == domain::Subdomains::RankBoxes ? "merged" : "blocks";
    summary.sync = std::string(toString(scene.sync.method));
    fillLoopSummary(world, stats, sim.grains(), summary);
    summary.peakRssBytes = peakRssBytes(world);
    summary.time = sim.time();
    summary.conserved = conservedNow(sim, scene);
    summary.gravity.method = scene.gravity.self;
    for (AutoChoice const& c : run.choices)
        summary.autoChoices.push_back({c.key, c.value, c.reason});
    if (sim.selfGravity())
        summariseSelfGravity(*sim.selfGravity(), scene, summary);
    summary.walls = reduceWallLoads(world, sim.dem().walls());
    summary.checksum = stateChecksumFrom(world, masters);
    if (ctx.isRoot() && !ctx.options.quiet)
        printRunReport(summary, stats.leftDomain, stats.timers);
    tryWrite(run.summaryFile, [&] { return toJson(summary); });
    if (!outputFailures.empty())
        throw core::InputError(outputFailures);
}

/// The run: prepared, started, stepped with the scene's outputs and the app's hooks as
/// observers, summarised. COLLECTIVE.
void runPrepared(core::AppContext& ctx, PreparedRun& run, SceneHooks const& hooks) {
    SceneDescription const& scene = run.scene;
    ParticleCounts const counts =
        countParticles(ctx.world, static_cast<std::int64_t>(run.placement.local->countMasters()));
    coupling::Simulation sim(ctx.world, simulationSetup(scene), std::move(run.placement));
    for (coupling::Simulation::BodyForces const& f : hooks.bodyForces)
        sim.addBodyForces(f);
    startRun(ctx, run, sim, counts);

    RunSummary summary;
    summary.initialConserved = conservedNow(sim, scene);
    RunOutputs outputs(
        ctx, scene, sim,
        {run.start.step, run.start.time, !ctx.options.restartPath.empty(), run.text, counts.total});
    outputs.observe(sim);
    for (SceneHooks::Observer const& o : hooks.observers)
        sim.addObserver(o.every, o.observe);
    coupling::RunStats const stats = sim.run(scene.time.steps - run.start.step);
    summary.balance = outputs.finish();
    summary.inserted = outputs.inserted();
    if (stats.leftThroughWalls > 0)
        core::log::warn("{} grain(s) passed through a wall and left the domain (the first, {}): "
                        "a grain moved farther than its radius in one step; reduce time.dt",
                        stats.leftThroughWalls, stats.firstWallCrossing);
    writeRunOutcome(ctx, run, sim, stats, std::move(summary));
}

} // namespace

int runScene(core::AppContext& ctx) {
    return runSceneWith(ctx, {});
}

int runSceneWith(core::AppContext& ctx, SceneHooks const& hooks) {
    try {
        PreparedRun run = prepareRun(ctx);
        runPrepared(ctx, run, hooks);
        return 0;
    } catch (core::InputError const& e) {
        // A check that compares several values names its key; say where the scene set it, as
        // the scene reader's own errors do (the same on every rank: so is the message).
        std::string const entryKey = locateSceneKey(ctx.scene, e.what());
        throw core::InputError(entryKey != e.what() ? entryKey
                                                    : locateSectionKey(ctx.scene, e.what()));
    }
}

} // namespace regolith::apps
