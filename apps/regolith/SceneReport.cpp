#include "apps/regolith/SceneReport.hpp"

#include "core/log/Printable.hpp"
#include "coupling/gravity/GravityMethod.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <string>

namespace regolith::apps {

namespace {

/// " (poisson fft)" for a mesh method that solves with the FFT; empty otherwise.
std::string poissonNote(GravitySection const& g) {
    coupling::GravityMethodEntry const* method = coupling::findGravityMethod(g.self);
    bool const mesh = method && method->usesGrid;
    return mesh && g.poisson != "petsc" ? " (poisson " + g.poisson + ")" : std::string();
}

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
                      domain::BlockForest const& forest, std::size_t particleSubdomains,
                      ParticleCounts const& particles, std::int64_t startStep) {
    auto const& d = forest.domain();
    auto const& n = forest.rootBlocks();
    // The name and path as text a terminal shows whole (a NUL would cut the report short).
    std::string text = fmt::format("{}: scene '{}' ({})\n", ctx.appName,
                                   core::printable(scene.name), core::printable(ctx.sceneName));
    text +=
        fmt::format("  domain [{}, {}, {}] - [{}, {}, {}], periodic: {}\n", d.min.x(), d.min.y(),
                    d.min.z(), d.max.x(), d.max.y(), d.max.z(), axes(forest.periodic()));
    text += fmt::format("  {} blocks ({} x {} x {} root, deepest level {}) on {} rank{}, {} idle; "
                        "the particles on {} subdomain{} ({})\n",
                        forest.globalBlockCount(), n[0], n[1], n[2], forest.maxLevel(),
                        ctx.world.size(), ctx.world.size() == 1 ? "" : "s", forest.idleRankCount(),
                        particleSubdomains, particleSubdomains == 1 ? "" : "s",
                        scene.sync.subdomains == domain::Subdomains::RankBoxes
                            ? "each rank's blocks merged"
                            : "one per block");
    // A restart runs the steps from the checkpoint's on (time.steps is a total).
    std::string const steps =
        startStep > 0 ? fmt::format("{} steps (from step {} to {})", scene.time.steps - startStep,
                                    startStep, scene.time.steps)
                      : fmt::format("{} steps", scene.time.steps);
    text += fmt::format("  {} of dt = {}, sync {}{}, contact {}, self-gravity {}{}, "
                        "{} walls\n",
                        steps, scene.time.dt, toString(scene.sync.method),
                        scene.sync.reproducible ? " (reproducible)" : "", scene.contact.model,
                        scene.gravity.self, poissonNote(scene.gravity), scene.walls.size());
    text += startStep > 0
                ? fmt::format("  {} particles from the checkpoint ({} to {} per rank)\n",
                              particles.total, particles.minPerRank, particles.maxPerRank)
                : fmt::format("  {} particles from {} [[particles]] entries ({} to {} per rank)\n",
                              particles.total, scene.particles.size(), particles.minPerRank,
                              particles.maxPerRank);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
}

void printRunReport(RunSummary const& summary, std::int64_t leftDomain,
                    core::TimerReport const& timers) {
    std::string text = fmt::format(
        "  {} steps in {:.4g} s ({:.4g} particle updates per core-second): {} particles, {} "
        "shadows at the end, {} left the domain\n",
        summary.steps, summary.wallSeconds, pupcs(summary), summary.particles, summary.shadows,
        leftDomain);
    text +=
        fmt::format("  messages per step {:.4g}, bytes per step {:.4g}, at most {} peers\n",
                    summary.comm.messagesPerStep, summary.comm.bytesPerStep, summary.comm.maxPeers);
    if (summary.ranks > 1)
        text += fmt::format("  load imbalance (max / mean) {:.3g} on average, {:.3g} at the end; "
                            "{} rebalance(s) in {:.3g} s\n",
                            summary.balance.meanImbalance, summary.balance.finalImbalance,
                            summary.balance.rebalances, summary.balance.seconds);
    text += timers.format();
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
}

} // namespace regolith::apps
