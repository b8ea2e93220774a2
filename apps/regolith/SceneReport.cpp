#include "apps/regolith/SceneReport.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <string>

namespace regolith::apps {

namespace {

std::string axes(std::array<bool, 3> const& periodic) {
    std::string out;
    for (int d = 0; d < 3; ++d)
        if (periodic[static_cast<std::size_t>(d)])
            out += out.empty() ? std::string(1, "xyz"[d]) : fmt::format(" {}", "xyz"[d]);
    return out.empty() ? "none" : out;
}

} // namespace

ParticleCounts countParticles(core::Comm const& comm, std::int64_t local) {
    auto const n = static_cast<long long>(local);
    return {comm.allReduce(n, core::ReduceOp::Sum), comm.allReduce(n, core::ReduceOp::Min),
            comm.allReduce(n, core::ReduceOp::Max)};
}

void printSceneReport(core::AppContext const& ctx, SceneDescription const& scene,
                      domain::BlockForest const& forest, ParticleCounts const& particles) {
    auto const& d = forest.domain();
    auto const& n = forest.rootBlocks();
    std::string text = fmt::format("{}: scene '{}' ({})\n", ctx.appName, scene.name, ctx.sceneName);
    text +=
        fmt::format("  domain [{}, {}, {}] - [{}, {}, {}], periodic: {}\n", d.min.x(), d.min.y(),
                    d.min.z(), d.max.x(), d.max.y(), d.max.z(), axes(forest.periodic()));
    text += fmt::format("  {} blocks ({} x {} x {} root, deepest level {}) on {} ranks, {} idle\n",
                        forest.globalBlockCount(), n[0], n[1], n[2], forest.maxLevel(),
                        ctx.world.size(), forest.idleRankCount());
    text += fmt::format("  {} steps of dt = {} requested, sync {}, contact {}, self-gravity {}, "
                        "{} walls\n",
                        scene.time.steps, scene.time.dt, toString(scene.sync.method),
                        toString(scene.contact.model), toString(scene.gravity.self),
                        scene.walls.size());
    text += fmt::format("  {} particles from {} [[particles]] entries ({} to {} per rank)\n",
                        particles.total, scene.particles.size(), particles.minPerRank,
                        particles.maxPerRank);
    text += "  initial state only: time stepping arrives with synchronisation (0 steps run)\n";
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
}

} // namespace regolith::apps
