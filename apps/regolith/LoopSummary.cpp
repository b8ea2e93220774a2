#include "apps/regolith/LoopSummary.hpp"

#include "particles/simulation/DemStep.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace regolith::apps {

MasterSource masterSource(particles::LocalParticles const& local) {
    return [&local](MasterVisit const& visit) {
        for (particles::BlockParticles const& bp : local.blocks()) {
            particles::ParticleStorage const& ps = bp.particles;
            ps.forEachMaster([&](std::size_t i) {
                MasterRecord m;
                static_cast<particles::GrainRow&>(m) = ps.row(i);
                visit(m);
            });
        }
    };
}

std::vector<MasterRecord> masterRecords(particles::LocalParticles const& local) {
    std::vector<MasterRecord> out;
    out.reserve(local.countMasters());
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            MasterRecord& m = out.emplace_back();
            static_cast<particles::GrainRow&>(m) = ps.row(i);
            m.fields = ps.fieldValues(i);
        });
    }
    return out;
}

namespace {

double averageSeconds(core::TimerReport const& report, std::string_view phase) {
    core::TimerStats const* row = report.find(phase);
    return row ? row->avg : 0.0;
}

} // namespace

void fillLoopSummary(core::Comm const& comm, coupling::RunStats const& loop,
                     particles::LocalParticles const& local, RunSummary& summary) {
    std::array<long long, 2> counts{static_cast<long long>(local.countMasters()),
                                    static_cast<long long>(local.countCopies())};
    comm.allReduceInPlace(std::span<long long>(counts), core::ReduceOp::Sum);
    summary.particles = counts[0];
    summary.shadows = counts[1] - counts[0];
    summary.steps = loop.steps;
    summary.wallSeconds = loop.wallSeconds;
    summary.leftDomain = loop.leftDomain;
    summary.leftThroughWalls = loop.leftThroughWalls;
    summary.timing.sync = averageSeconds(loop.timers, particles::DemStep::kSyncTimer);
    summary.timing.contact = averageSeconds(loop.timers, particles::DemStep::kContactTimer);
    summary.timing.gravity = averageSeconds(loop.timers, particles::DemStep::kBodyForceTimer);
    summary.timing.integrate = averageSeconds(loop.timers, particles::DemStep::kIntegrateTimer);
    if (loop.steps > 0) {
        auto const steps = static_cast<double>(loop.steps);
        summary.comm.messagesPerStep = static_cast<double>(loop.comm.messages) / steps;
        summary.comm.bytesPerStep = static_cast<double>(loop.comm.bytes) / steps;
    }
    summary.comm.maxPeers = loop.comm.maxPeers;
    summary.neighbourList.skin = loop.listSkin;
    summary.neighbourList.rebuilds = loop.listRebuilds;
    summary.neighbourList.shifts = loop.listShifts;
}

} // namespace regolith::apps
