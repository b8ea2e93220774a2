#include "apps/regolith/SpeedChoices.hpp"

#include "core/Error.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace regolith::apps {

namespace {

double smallestRadius(core::Comm const& comm, particles::LocalParticles const& local) {
    double r = std::numeric_limits<double>::infinity();
    for (particles::BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) { r = std::min(r, bp.particles.radius(i)); });
    return comm.allReduce(r, core::ReduceOp::Min);
}

} // namespace

std::vector<AutoChoice> resolveSpeedChoices(core::Comm const& comm,
                                            particles::LocalParticles const& local,
                                            SceneDescription& scene) {
    std::vector<AutoChoice> out;
    TimeSection& time = scene.time;
    if (time.orientationAuto) {
        time.orientationAuto = false;
        if (time.integrator == Integrator::Euler) {
            time.orientation = true;
            out.push_back({"time.orientation", "true", "semi-implicit Euler integrates it"});
        } else {
            OutputSection const& o = scene.output;
            bool const hdf5Snapshots = o.dumpFormat == DumpFormat::Hdf5 && o.dumpEvery > 0;
            time.orientation =
                (o.checkpointEvery > 0 && o.checkpointEvery <= time.steps) || hdf5Snapshots;
            out.push_back({"time.orientation", time.orientation ? "true" : "false",
                           time.orientation ? "the checkpoints store the grains' orientation"
                                            : "spheres, and no output writes an orientation"});
        }
    }
    SyncSection& sync = scene.sync;
    if (!sync.skinAuto)
        return out;
    sync.skinAuto = false;
    sync.skin = 0.0;
    if (sync.method == particles::SyncMethod::ShadowOwner) {
        out.push_back({"sync.skin", "0", "sync.method = \"sos\" decides every shadow each step"});
        return out;
    }
    double const r = smallestRadius(comm, local);
    if (!std::isfinite(r)) {
        out.push_back({"sync.skin", "0", "no grains"});
        return out;
    }
    double const skin = kAutoSyncSkinPerRadius * r;
    if (sync.method == particles::SyncMethod::NextNeighbour) {
        particles::SyncConfig grown = sync;
        grown.skin = skin;
        particles::ParticleSync const probe(comm, local.forest(), grown);
        auto const violation = probe.findNnsViolation(local);
        bool const refused = comm.allReduce(violation ? 1 : 0, core::ReduceOp::Max) != 0;
        bool const anyway =
            comm.allReduce(violation && violation->radiusAlone ? 1 : 0, core::ReduceOp::Max) != 0;
        if (refused) {
            out.push_back({"sync.skin", "0",
                           anyway
                               ? std::string("sync.method = \"nns\" refuses a grain of this scene "
                                             "whatever the skin (below)")
                               : fmt::format("a grain's ball grown by {:g} would reach past the "
                                             "subdomains next to it, which sync.method = \"nns\" "
                                             "refuses",
                                             skin)});
            return out;
        }
    }
    sync.skin = skin;
    out.push_back({"sync.skin", fmt::format("{}", skin),
                   fmt::format("a quarter of the smallest grain radius {:g}: shadows decided "
                               "as often as the Verlet lists",
                               r)});
    return out;
}

} // namespace regolith::apps
