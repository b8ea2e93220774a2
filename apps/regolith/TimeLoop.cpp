#include "apps/regolith/TimeLoop.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace regolith::apps {

LoopOutcome runTimeLoop(core::Comm const& comm, particles::DemStep& dem,
                        particles::ParticleSync& sync, core::TimerTree& timers, std::int64_t steps,
                        AfterStep const& afterStep, ObservesStep const& observes) {
    timers.reset();
    sync.resetCounters();
    std::uint64_t const leftBefore = dem.leftDomain();
    std::uint64_t const crossedBefore = dem.wallCrossings().count;
    std::uint64_t const rebuildsBefore = dem.listRebuilds();
    comm.barrier(); // every rank starts the clock together
    double const start = MPI_Wtime();
    for (std::int64_t n = 0; n < steps; ++n) {
        auto const next = static_cast<std::int64_t>(dem.stepsDone()) + 1;
        bool const open = n + 1 < steps && observes && !observes(next);
        dem.step(open ? particles::DemStep::StepEnd::Open : particles::DemStep::StepEnd::Complete);
        if (afterStep)
            afterStep(static_cast<std::int64_t>(dem.stepsDone()));
    }
    double const elapsed = MPI_Wtime() - start;

    LoopOutcome out;
    out.steps = steps;
    out.wallSeconds = comm.allReduce(elapsed, core::ReduceOp::Max);
    out.timers = timers.reduce(comm);
    out.comm = sync.counters().reduce(comm);
    auto const& crossings = dem.wallCrossings();
    std::array<long long, 3> counts{static_cast<long long>(dem.leftDomain() - leftBefore),
                                    static_cast<long long>(dem.listRebuilds() - rebuildsBefore),
                                    static_cast<long long>(crossings.count - crossedBefore)};
    comm.allReduceInPlace(std::span<long long>(counts), core::ReduceOp::Sum);
    out.leftDomain = counts[0];
    out.listRebuilds = counts[1];
    out.leftThroughWalls = counts[2];
    if (out.leftThroughWalls > 0) { // the earliest step's, lowest uid's (every rank is here)
        bool const mine = crossings.count > crossedBefore;
        auto const when = comm.allGather<std::uint64_t>(
            mine ? crossings.firstStep : std::numeric_limits<std::uint64_t>::max());
        auto const uids = comm.allGather<std::uint64_t>(crossings.firstUid);
        auto const walls = comm.allGather<std::uint64_t>(crossings.firstWall);
        std::size_t first = 0;
        for (std::size_t r = 1; r < when.size(); ++r)
            if (when[r] < when[first] || (when[r] == when[first] && uids[r] < uids[first]))
                first = r;
        out.firstWallCrossing = fmt::format("particle uid {} at step {} through walls[{}]",
                                            uids[first], when[first], walls[first]);
    }
    out.listSkin = comm.allReduce(dem.listSkin(), core::ReduceOp::Max);
    return out;
}

MasterSource masterSource(particles::LocalParticles const& local) {
    return [&local](MasterVisit const& visit) {
        for (particles::BlockParticles const& bp : local.blocks()) {
            particles::ParticleStorage const& ps = bp.particles;
            ps.forEachMaster([&](std::size_t i) {
                visit({ps.uid(i), ps.position(i), ps.velocity(i), ps.angularVelocity(i),
                       ps.radius(i), ps.mass(i)});
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
            out.push_back({ps.uid(i), ps.position(i), ps.velocity(i), ps.angularVelocity(i),
                           ps.radius(i), ps.mass(i)});
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

void fillLoopSummary(core::Comm const& comm, LoopOutcome const& loop,
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
}

} // namespace regolith::apps
