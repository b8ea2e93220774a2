// regolith: the generic scene driver. Reads a scene (or runs the embedded default scene),
// builds the block forest, generates the initial particles on every rank and writes the run
// summary and dump (DESIGN.md, "Contracts"). Usage: regolith --help.
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
#include "core/Error.hpp"
#include "core/app/RunApp.hpp"
#include "core/log/Log.hpp"
#include "domain/BlockForest.hpp"

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
    particles::ParticleStorage const particles = apps::makeMasters(grains, forest, world.rank());
    apps::checkInitialState(world, particles, scene);
    auto const masters = apps::toMasterRecords(grains);
    auto const counts = apps::countParticles(world, static_cast<std::int64_t>(masters.size()));
    if (ctx.isRoot() && !ctx.options.quiet)
        apps::printSceneReport(ctx, scene, forest, counts);
    if (forest.idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        forest.idleRankCount(), world.size());
    auto const wallOverlaps = world.allReduce(
        static_cast<long long>(apps::countWallOverlaps(masters, scene.walls)), core::ReduceOp::Sum);
    if (wallOverlaps > 0)
        core::log::warn("{} of {} grains overlap a wall at the start", wallOverlaps, counts.total);

    // The time-step loop (DESIGN.md, "The time step") arrives with the synchronisation issue:
    // until then the run is the initial state, no step is executed, and wall_s times this
    // (empty) loop only, set-up and output excluded.
    std::int64_t const stepsRun = 0;
    double const loopStart = MPI_Wtime();
    double const wall = world.allReduce(MPI_Wtime() - loopStart, core::ReduceOp::Max);

    if (!ctx.options.dumpPath.empty())
        apps::writeFileOnRoot(world, ctx.options.dumpPath, apps::gatherDumpCsv(world, masters));

    apps::RunSummary summary;
    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(forest.globalBlockCount());
    summary.sync = std::string(apps::toString(scene.sync.method));
    summary.particles = counts.total;
    summary.steps = stepsRun;
    summary.wallSeconds = wall;
    summary.peakRssBytes = apps::peakRssBytes(world);
    summary.conserved = apps::conservedQuantities(world, masters, scene.gravity.external);
    summary.checksum = apps::stateChecksum(world, masters);
    if (!ctx.options.jsonPath.empty())
        apps::writeFileOnRoot(world, ctx.options.jsonPath, apps::toJson(summary));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return core::runApp(argc, argv, "regolith", apps::defaultScene(), runScene);
}
