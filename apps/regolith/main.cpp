// regolith: the generic scene driver. Reads a scene (or runs the embedded default scene),
// builds the block forest, generates the initial particles on every rank, runs the DEM time
// steps with shadow synchronisation and writes the run summary and dump (DESIGN.md,
// "Contracts"). Usage: regolith --help.
#include "apps/common/ConservedQuantities.hpp"
#include "apps/common/OutputFile.hpp"
#include "apps/common/RunSummary.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/common/StateDump.hpp"
#include "apps/regolith/DefaultScene.hpp"
#include "apps/regolith/InitialState.hpp"
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/SceneReport.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/regolith/TimeLoop.hpp"
#include "core/Error.hpp"
#include "core/app/RunApp.hpp"
#include "core/log/Log.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <string>

namespace {

using namespace regolith;

int runScene(core::AppContext& ctx) {
    core::Comm const& world = ctx.world;
    apps::SceneDescription const scene = apps::parseScene(ctx.scene, ctx.options.scenePath);
    if (!ctx.options.restartPath.empty())
        throw core::InputError(fmt::format("--restart {}: restarting from a checkpoint needs the "
                                           "HDF5 checkpoint reader of the io module, which this "
                                           "build does not have yet",
                                           ctx.options.restartPath));
    // Fail before the run, not after it, if an output file cannot be written.
    if (!ctx.options.jsonPath.empty())
        apps::checkWritable(world, ctx.options.jsonPath, "--json");
    if (!ctx.options.dumpPath.empty())
        apps::checkWritable(world, ctx.options.dumpPath, "--dump");

    domain::BlockForest const forest(world, scene.forest);
    auto const grains = apps::generateLocalGrains(world, ctx.scene, scene, forest);
    apps::checkInitialState(world, apps::makeMasters(grains, forest, world.rank()), scene);
    auto const counts = apps::countParticles(world, static_cast<std::int64_t>(grains.size()));
    if (ctx.isRoot() && !ctx.options.quiet)
        apps::printSceneReport(ctx, scene, forest, counts);
    if (forest.idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        forest.idleRankCount(), world.size());
    auto const wallOverlaps = world.allReduce(
        static_cast<long long>(apps::countWallOverlaps(apps::toMasterRecords(grains), scene.walls)),
        core::ReduceOp::Sum);
    if (wallOverlaps > 0)
        core::log::warn("{} of {} grains overlap a wall at the start", wallOverlaps, counts.total);

    // The particles of this rank's blocks, their shadows, and the time step (DESIGN.md, "The
    // time step"): NNS refuses a grain too large for it (InputError, exit 2 on every rank),
    // then every shadow is created and the initial forces computed.
    particles::LocalParticles local(forest);
    apps::addMasters(local, grains);
    particles::ParticleSync sync(world, forest, scene.sync);
    core::TimerTree timers([] { return MPI_Wtime(); });
    particles::DemStepConfig stepConfig;
    stepConfig.dt = scene.time.dt;
    stepConfig.gravity = scene.gravity.external;
    particles::DemStep dem(world, sync, local, apps::makeContactModel(scene),
                           apps::makeIntegrator(scene), apps::makeWalls(scene), stepConfig, timers);
    dem.setUp();
    apps::checkOverlapsAcrossBlocks(world, local, dem.contacts(), scene.contact.initialOverlap);

    apps::LoopOutcome const loop = apps::runTimeLoop(world, dem, sync, timers, scene.time.steps);

    auto const masters = apps::masterRecords(local);
    if (!ctx.options.dumpPath.empty())
        apps::writeFileOnRoot(world, ctx.options.dumpPath, apps::gatherDumpCsv(world, masters));

    apps::RunSummary summary;
    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(forest.globalBlockCount());
    summary.sync = std::string(apps::toString(scene.sync.method));
    apps::fillLoopSummary(world, loop, local, summary);
    summary.peakRssBytes = apps::peakRssBytes(world);
    summary.conserved = apps::conservedQuantities(world, masters, scene.gravity.external);
    summary.checksum = apps::stateChecksum(world, masters);
    if (ctx.isRoot() && !ctx.options.quiet)
        apps::printRunReport(summary, loop.leftDomain, loop.timers);
    if (!ctx.options.jsonPath.empty())
        apps::writeFileOnRoot(world, ctx.options.jsonPath, apps::toJson(summary));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return core::runApp(argc, argv, "regolith", apps::defaultScene(), runScene);
}
