// regolith: the generic scene driver. Reads a scene (or runs the embedded default scene),
// builds the block forest, runs the scene and writes the run summary (DESIGN.md,
// "Contracts"). Usage: regolith --help.
#include "apps/common/OutputFile.hpp"
#include "apps/common/RunSummary.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/regolith/DefaultScene.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/app/RunApp.hpp"
#include "core/log/Log.hpp"
#include "domain/BlockForest.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdio>
#include <string>

namespace {

using namespace regolith;

constexpr char const* kDumpHeader = "uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass\n";

std::string axes(std::array<bool, 3> const& periodic) {
    std::string out;
    for (int d = 0; d < 3; ++d)
        if (periodic[static_cast<std::size_t>(d)])
            out += out.empty() ? std::string(1, "xyz"[d]) : fmt::format(" {}", "xyz"[d]);
    return out.empty() ? "none" : out;
}

/// The one-paragraph report printed by rank 0 before the run.
void printSummary(core::AppContext const& ctx, apps::SceneDescription const& scene,
                  domain::BlockForest const& forest, std::int64_t particles) {
    auto const& d = forest.domain();
    auto const& n = forest.rootBlocks();
    std::printf("%s: scene '%s' (%s)\n", ctx.appName.c_str(), scene.name.c_str(),
                ctx.sceneName.c_str());
    std::printf("  domain [%g, %g, %g] - [%g, %g, %g], periodic: %s\n", d.min.x(), d.min.y(),
                d.min.z(), d.max.x(), d.max.y(), d.max.z(), axes(forest.periodic()).c_str());
    std::printf("  %zu blocks (%d x %d x %d root, deepest level %d) on %d ranks, %d idle\n",
                forest.globalBlockCount(), n[0], n[1], n[2], forest.maxLevel(), ctx.world.size(),
                forest.idleRankCount());
    std::printf("  %lld steps of dt = %g, sync %s, contact %s, self-gravity %s, %zu walls\n",
                static_cast<long long>(scene.time.steps), scene.time.dt,
                std::string(apps::toString(scene.sync.method)).c_str(),
                std::string(apps::toString(scene.contact.model)).c_str(),
                std::string(apps::toString(scene.gravity.self)).c_str(), scene.walls.size());
    std::printf("  %lld particles: %zu particle source(s) validated; generating them and stepping "
                "arrive with the particles module\n",
                static_cast<long long>(particles), scene.particles.size());
    std::fflush(stdout);
}

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

    // Particles come from scene.particles once the particles module has its generators; the
    // state is empty until then (and so are shadows, contacts and the conserved quantities).
    std::int64_t const particles = 0;
    if (ctx.isRoot() && !ctx.options.quiet)
        printSummary(ctx, scene, forest, particles);
    if (forest.idleRankCount() > 0)
        core::log::warn("{} of {} ranks own no block: use more blocks (domain.blocks) or fewer "
                        "ranks",
                        forest.idleRankCount(), world.size());

    // The time-step loop (DESIGN.md, "The time step"): with an empty state there is nothing
    // to advance yet; wall_s measures this loop only, set-up and output excluded.
    double const loopStart = MPI_Wtime();
    double const wall = world.allReduce(MPI_Wtime() - loopStart, core::ReduceOp::Max);

    apps::StateChecksum checksum; // over the uid-sorted final state: empty
    if (!ctx.options.dumpPath.empty())
        apps::writeFileOnRoot(world, ctx.options.dumpPath, kDumpHeader);

    apps::RunSummary summary;
    summary.scene = scene.name;
    summary.ranks = world.size();
    summary.blocks = static_cast<std::int64_t>(forest.globalBlockCount());
    summary.sync = std::string(apps::toString(scene.sync.method));
    summary.particles = particles;
    summary.steps = scene.time.steps;
    summary.wallSeconds = wall;
    summary.peakRssBytes = apps::peakRssBytes(world);
    summary.checksum = checksum.hex();
    if (!ctx.options.jsonPath.empty())
        apps::writeFileOnRoot(world, ctx.options.jsonPath, apps::toJson(summary));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return core::runApp(argc, argv, "regolith", apps::defaultScene(), runScene);
}
