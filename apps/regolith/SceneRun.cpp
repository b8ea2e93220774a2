// The generic scene run behind `regolith` and the reference-scene apps: builds the block
// forest, generates the initial particles on every rank, runs the DEM time steps with shadow
// synchronisation and writes the run summary and dump (docs/design.md, "Contracts"), checkpoints
// (output.checkpoint_every) and restarts from one (--restart).
#include "apps/regolith/SceneRun.hpp"

#include "apps/common/ConservedQuantities.hpp"
#include "apps/common/OutputFile.hpp"
#include "apps/common/RunSummary.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/common/StateDump.hpp"
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/BlockPlacement.hpp"
#include "apps/regolith/Checkpointing.hpp"
#include "apps/regolith/DynamicBalance.hpp"
#include "apps/regolith/GrainPouring.hpp"
#include "apps/regolith/GravitySetup.hpp"
#include "apps/regolith/GridAccuracy.hpp"
#include "apps/regolith/InitialState.hpp"
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/ParticleSnapshots.hpp"
#include "apps/regolith/ProgressLine.hpp"
#include "apps/regolith/RunPaths.hpp"
#include "apps/regolith/SceneKeyLocation.hpp"
#include "apps/regolith/SceneReport.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/regolith/SpeedChoices.hpp"
#include "apps/regolith/ThermoLog.hpp"
#include "apps/regolith/TimeLoop.hpp"
#include "apps/regolith/WallLoads.hpp"
#include "apps/scenarios/Scenarios.hpp"
#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "io/vtk/VtkOutput.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

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

/// The grid fields for VTK output: those of grid gravity once computed, else none.
std::optional<gravity::GridFieldsView> gridFieldsOf(coupling::SelfGravityForces const* gravity) {
    return gravity != nullptr ? gravity->gridFields() : std::nullopt;
}

int runSceneUnlocated(core::AppContext& ctx) {
    core::Comm const& world = ctx.world;
    expandScenarios(ctx.scene, world.size());
    SceneDescription scene = parseScene(ctx.scene, ctx.options.scenePath);
    bool const restart = !ctx.options.restartPath.empty();
    // Fail before the run, not after it, if an output file would overwrite an input or
    // another output, or cannot be written.
    checkRunPaths(world, ctx.options, scene);
    std::string const summaryFile = summaryPath(ctx.options, scene);
    checkWritable(world, summaryFile, ctx.options.jsonPath.empty() ? "the run summary" : "--json");
    if (!ctx.options.dumpPath.empty())
        checkWritable(world, ctx.options.dumpPath, "--dump");

    // The particles of this rank's blocks: masters now, shadows from the set-up's sync. They
    // are placed on equally weighted blocks, then the blocks are re-assigned by their load.
    BlockPlacement placement = uniformPlacement(world, scene);
    // Before any grain is made: the blocks' geometry is final here (balancing moves owners).
    requireSkinBelowBlockEdges(world, *placement.forest, scene.contact.neighbourSkin);
    std::string text = sceneText(ctx); // stored in checkpoints, compared on a restart
    std::vector<AutoChoice> choices;
    RunStart start;
    if (restart) {
        // "auto" takes what the checkpoint's run chose, before the checkpoint's dt is compared.
        double const started = MPI_Wtime();
        io::CheckpointSlice slice = io::readCheckpoint(world, ctx.options.restartPath);
        requireSameDomain(ctx.options.restartPath, slice.info, scene); // the first question
        choices = reuseAutoChoices(ctx, scene, slice.info.scene);
        text = withAutoChoices(std::move(text), choices);
        start = restoreState(ctx, scene, text, std::move(slice), started, *placement.local);
    } else {
        choices = generateInitialState(ctx, scene, *placement.particleForest, *placement.local);
        text = withAutoChoices(std::move(text), choices);
    }
    std::int64_t const startStep = start.step;
    balanceByLoad(world, scene, placement);
    domain::BlockForest const& forest = *placement.forest;
    particles::LocalParticles& local = *placement.local;
    // Not in the checkpoint's scene text: they change the speed, not the trajectory.
    for (AutoChoice& c : resolveSpeedChoices(world, local, scene))
        choices.push_back(std::move(c));
    // Simulated time after a step: continued from the checkpoint's (its dt may differ).
    auto const timeAt = [&](std::int64_t step) {
        return start.time + static_cast<double>(step - startStep) * scene.time.dt;
    };
    if (ctx.isRoot() && !ctx.options.quiet)
        for (AutoChoice const& c : choices)
            fmt::print("  auto: {} = {} ({})\n", c.key, c.value, c.reason);
    auto const selfGravity = makeSelfGravity(world, forest, scene);
    if (selfGravity && start.checkpoint) {
        restoreSelfGravity(*start.checkpoint, *selfGravity); // cached field, update policy
        if (scene.output.vtkEvery > 0) // the restart step's grid output, like every other's
            selfGravity->refreshGridFields(local);
    }
    start.checkpoint.reset(); // the grains are in `local` now
    auto const counts = countParticles(world, static_cast<std::int64_t>(local.countMasters()));
    if (ctx.isRoot() && !ctx.options.quiet)
        printSceneReport(ctx, scene, forest, placement.particleForest->globalSubdomainCount(),
                         counts, startStep);
    if (forest.idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        forest.idleRankCount(), world.size());
    auto const wallOverlaps =
        world.allReduce(static_cast<long long>(countWallOverlaps(masterSource(local), scene.walls)),
                        core::ReduceOp::Sum);
    if (wallOverlaps > 0 && !restart)
        core::log::warn("{} of {} grains overlap a wall at the start", wallOverlaps, counts.total);

    // The time step (docs/design.md, "The time step"): NNS refuses a grain too large for it
    // (InputError, exit 2 on every rank), then every shadow is created and, for a new run,
    // the initial forces computed (a restart has them from the checkpoint).
    particles::ParticleSync sync(world, *placement.particleForest, scene.sync);
    core::TimerTree timers([] { return MPI_Wtime(); });
    particles::DemStepConfig stepConfig;
    stepConfig.dt = scene.time.dt;
    stepConfig.gravity = scene.gravity.external;
    stepConfig.keepContacts = false;   // read after setUp only (checkOverlapsAcrossBlocks)
    if (scene.contact.neighbourSkin) { // else DemStep's default, relative to the radius
        stepConfig.detector.skin = *scene.contact.neighbourSkin;
        stepConfig.detector.relativeSkin = 0.0;
    }
    particles::DemStep dem(world, sync, local, makeContactModel(scene), makeIntegrator(scene),
                           makeWalls(scene), stepConfig, timers);
    // Self-gravity as the step's body forces (after contacts and their reduction).
    if (selfGravity)
        dem.setBodyForces(
            [g = selfGravity.get()](particles::LocalParticles& l) { g->addForces(l); });
    if (restart) {
        dem.resume(static_cast<std::uint64_t>(startStep), start.time);
    } else {
        dem.setUp();
        checkOverlapsAcrossBlocks(world, local, dem.contacts(), scene.contact.initialOverlap);
        if (selfGravity) // the first field's error, on this scene's grains
            checkMeasuredGridAccuracy(*selfGravity, scene);
    }

    // The conserved quantities at the loop's start (the summary's "conserved_initial").
    auto const selfPotential = [&] {
        return selfGravity ? selfGravity->stats().potentialEnergy : 0.0;
    };
    RunSummary::Conserved initial =
        conservedQuantitiesFrom(world, masterSource(local), scene.gravity.external);
    initial.potentialEnergy += selfPotential();

    // Output during the run: checkpoints, VTK files (the start state too), the progress line.
    CheckpointSchedule checkpoints(world, scene, text, local, timeAt);
    checkpoints.setSelfGravity(selfGravity.get());
    checkpoints.checkReplaced(startStep, scene.time.steps);
    ParticleSnapshots snapshots(world, scene.output, local, checkpoints);
    if (!restart && snapshots.due(startStep))
        snapshots.write(startStep);
    std::optional<io::VtkOutput> vtk;
    if (scene.output.vtkEvery > 0) {
        // A restart continues the series of the run it restarts (the entries before it).
        io::VtkOptions options{scene.output.dir, scene.output.vtkShadows, true};
        if (restart)
            options.keepEntriesBefore = start.time;
        options.writesGrid = gridFieldsOf(selfGravity.get()).has_value();
        options.writesWalls = !dem.walls().empty();
        vtk.emplace(world, options);
    }
    // The grains, blocks, grid and walls of one output frame.
    auto const writeVtk = [&](std::int64_t step) {
        vtk->write(step, timeAt(step), local, gridFieldsOf(selfGravity.get()));
        if (!dem.walls().empty())
            vtk->writeWalls(step, timeAt(step), dem.walls(), forest.geometry().domain());
    };
    if (vtk)
        writeVtk(startStep);
    ProgressLine progress(ProgressSettings{
        startStep, start.time, scene.time.steps, scene.time.dt, counts.total,
        std::string(toString(scene.sync.method)), std::string(toString(scene.gravity.self)),
        world.size(), scene.output.progressSeconds, ctx.isRoot() && !ctx.options.quiet});
    // A rebalance or an insertion moves the grains in place (BlockPlacement); what stands on
    // the blocks' assignment moves with them.
    auto const relocate = [&] {
        sync.relocate(*placement.particleForest);
        if (selfGravity)
            selfGravity->relocate(forest);
        dem.relocated();
        if (selfGravity && vtk) // the grid output until the next update (as on a restart)
            selfGravity->refreshGridFields(local);
    };
    DynamicBalance balance(world, scene, placement, startStep, relocate);
    GrainPouring pouring(world, scene, local);
    ThermoLog thermo(world, {thermoPath(scene), scene.output.thermoEvery, startStep, restart,
                             ctx.isRoot() && !ctx.options.quiet, dem.walls().size()});
    auto const writeThermo = [&](std::int64_t stepsDone) {
        thermo.write(measureThermo(world, local, dem.contacts(),
                                   {stepsDone, timeAt(stepsDone), scene.gravity.external,
                                    selfPotential(), balance.imbalance(), &dem.walls()}));
    };
    if (!restart && thermo.due(startStep)) // a restart has the row of its step from before
        writeThermo(startStep);
    dem.setKeepContacts(thermo.due(startStep + 1)); // the contacts a row counts
    auto const afterStep = [&](std::int64_t stepsDone) {
        // First: the step's contacts index the grains as they lie, before an insertion or a
        // rebalance moves them.
        if (thermo.due(stepsDone)) {
            progress.clear(); // the row gets a line of its own
            writeThermo(stepsDone);
        }
        dem.setKeepContacts(thermo.due(stepsDone + 1));
        if (pouring.due(stepsDone)) {
            progress.clear(); // a grain that found no place is warned about
            std::int64_t const before = pouring.inserted();
            if (pouring.afterStep(stepsDone, placement, dem.walls()))
                relocate();
            progress.addGrains(pouring.inserted() - before);
        }
        if (checkpoints.due(stepsDone))
            progress.clear(); // the checkpoint's log line gets a line of its own
        checkpoints.afterStep(stepsDone);
        if (vtk && stepsDone % scene.output.vtkEvery == 0)
            writeVtk(stepsDone);
        if (snapshots.due(stepsDone))
            snapshots.write(stepsDone);
        balance.afterStep(stepsDone);
        progress.setImbalance(balance.imbalance());
        if (selfGravity)
            progress.setForceError(selfGravity->measuredError().stats(),
                                   selfGravity->measuredError().checks());
        progress.afterStep(stepsDone);
    };
    // Only output, checkpoints and the load balance look at the grains between steps (the
    // progress line does not): the other steps end Open, their last half kick merged into the
    // next step's first.
    auto const observes = [&](std::int64_t stepsDone) {
        return checkpoints.due(stepsDone) || (vtk && stepsDone % scene.output.vtkEvery == 0) ||
               balance.due(stepsDone) || pouring.due(stepsDone) || thermo.due(stepsDone) ||
               snapshots.due(stepsDone);
    };
    LoopOutcome const loop =
        runTimeLoop(world, dem, sync, timers, scene.time.steps - startStep, afterStep, observes);
    progress.finish();
    if (loop.leftThroughWalls > 0)
        core::log::warn("{} grain(s) passed through a wall and left the domain (the first, {}): "
                        "a grain moved farther than its radius in one step; reduce time.dt",
                        loop.leftThroughWalls, loop.firstWallCrossing);

    dem.releaseWorkspace(); // the detectors' memory, before the summary below
    // The summary reads the masters from the storages (no record list of every grain: that
    // was the run's memory peak); only --dump gathers them, and frees them again at once.
    MasterSource const masters = masterSource(local);
    // A dump that cannot be written (a full disk) does not cost the summary: both are tried,
    // then every failure is reported.
    std::string outputFailures;
    auto const tryWrite = [&](std::string const& path, auto const& textOf) {
        try {
            writeFileOnRoot(world, path, textOf());
        } catch (core::InputError const& e) {
            outputFailures += (outputFailures.empty() ? "" : "\n") + std::string(e.what());
        }
    };
    if (!ctx.options.dumpPath.empty())
        tryWrite(ctx.options.dumpPath, [&] { return gatherDumpCsv(world, masterRecords(local)); });

    RunSummary summary;
    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(forest.globalBlockCount());
    summary.particleSubdomains =
        static_cast<std::int64_t>(placement.particleForest->globalSubdomainCount());
    summary.subdomains =
        scene.sync.subdomains == domain::Subdomains::RankBoxes ? "merged" : "blocks";
    summary.sync = std::string(toString(scene.sync.method));
    fillLoopSummary(world, loop, local, summary);
    summary.balance = balance.finish();
    summary.peakRssBytes = peakRssBytes(world);
    summary.time = timeAt(scene.time.steps);
    summary.initialConserved = initial;
    summary.conserved = conservedQuantitiesFrom(world, masters, scene.gravity.external);
    summary.gravity.method = std::string(toString(scene.gravity.self));
    for (AutoChoice const& c : choices)
        summary.autoChoices.push_back({c.key, c.value, c.reason});
    if (selfGravity) {
        // ½ Σ m φ of the last field computed: the final positions' when it is updated every
        // step (update_threshold = 0).
        summary.conserved.potentialEnergy += selfGravity->stats().potentialEnergy;
        summary.gravity.updates = selfGravity->stats().evaluations;
        summary.gravity.interval = selfGravity->updateInterval();
        coupling::ForceErrorMonitor const& measured = selfGravity->measuredError();
        summary.gravity.checks = measured.checks();
        summary.gravity.samples = measured.stats().count;
        summary.gravity.medianError = measured.stats().median;
        summary.gravity.p99Error = measured.stats().p99;
        summary.gravity.maxError = measured.stats().max;
        std::string const warning = measuredErrorWarning(
            measured, scene, selfGravity->stats().evaluations, selfGravity->stats().steps);
        if (!warning.empty())
            core::log::warn("{}", warning);
    }
    summary.walls = reduceWallLoads(world, dem.walls());
    summary.inserted = pouring.inserted();
    summary.checksum = stateChecksumFrom(world, masters);
    if (ctx.isRoot() && !ctx.options.quiet)
        printRunReport(summary, loop.leftDomain, loop.timers);
    tryWrite(summaryFile, [&] { return toJson(summary); });
    if (!outputFailures.empty())
        throw core::InputError(outputFailures);
    return 0;
}

} // namespace

int runScene(core::AppContext& ctx) {
    try {
        return runSceneUnlocated(ctx);
    } catch (core::InputError const& e) {
        // A check that compares several values names its key; say where the scene set it, as
        // the scene reader's own errors do (the same on every rank: so is the message).
        std::string const entryKey = locateSceneKey(ctx.scene, e.what());
        throw core::InputError(entryKey != e.what() ? entryKey
                                                    : locateSectionKey(ctx.scene, e.what()));
    }
}

} // namespace regolith::apps
