#include "apps/common/RunSummary.hpp"

#include "core/json/JsonWriter.hpp"

#include <span>
#include <sys/resource.h>

namespace regolith::apps {

double pupcs(RunSummary const& s) {
    if (!(s.wallSeconds > 0.0) || s.ranks <= 0)
        return 0.0;
    return static_cast<double>(s.steps) * static_cast<double>(s.particles) /
           (s.wallSeconds * static_cast<double>(s.ranks));
}

std::string toJson(RunSummary const& s) {
    core::JsonWriter w;
    w.beginObject()
        .member("scene", s.scene)
        .member("ranks", s.ranks)
        .member("blocks", s.blocks)
        .member("particle_subdomains", s.particleSubdomains)
        .member("subdomains", s.subdomains)
        .member("sync", s.sync)
        .member("particles", s.particles)
        .member("shadows", s.shadows)
        .member("left_domain", s.leftDomain)
        .member("left_through_walls", s.leftThroughWalls)
        .member("inserted", s.inserted)
        .member("steps", s.steps)
        .member("time", s.time)
        .member("wall_s", s.wallSeconds)
        .member("pupcs", pupcs(s))
        .member("peak_rss_bytes", s.peakRssBytes);
    w.key("timing_s")
        .beginObject()
        .member("sync", s.timing.sync)
        .member("contact", s.timing.contact)
        .member("gravity", s.timing.gravity)
        .member("integrate", s.timing.integrate)
        .endObject();
    w.key("gravity")
        .beginObject()
        .member("method", s.gravity.method)
        .member("updates", s.gravity.updates)
        .member("interval", s.gravity.interval);
    w.key("error")
        .beginObject()
        .member("checks", s.gravity.checks)
        .member("samples", s.gravity.samples)
        .member("median", s.gravity.medianError)
        .member("p99", s.gravity.p99Error)
        .member("max", s.gravity.maxError)
        .endObject()
        .endObject();
    w.key("balance")
        .beginObject()
        .member("every", s.balance.every)
        .member("threshold", s.balance.threshold)
        .member("rebalances", s.balance.rebalances)
        .member("splits", s.balance.splits)
        .member("seconds", s.balance.seconds)
        .member("mean_imbalance", s.balance.meanImbalance)
        .member("final_imbalance", s.balance.finalImbalance)
        .member("block_floor", s.balance.blockFloor);
    w.key("history")
        .beginObject()
        .member("step", std::span<double const>(s.balance.steps))
        .member("imbalance", std::span<double const>(s.balance.imbalances))
        .endObject()
        .endObject();
    w.key("auto").beginObject();
    for (RunSummary::AutoChoice const& c : s.autoChoices)
        w.key(c.key).beginObject().member("value", c.value).member("reason", c.reason).endObject();
    w.endObject();
    w.key("comm")
        .beginObject()
        .member("messages_per_step", s.comm.messagesPerStep)
        .member("bytes_per_step", s.comm.bytesPerStep)
        .member("max_peers", s.comm.maxPeers)
        .endObject();
    w.key("neighbour_list")
        .beginObject()
        .member("skin", s.neighbourList.skin)
        .member("rebuilds", s.neighbourList.rebuilds)
        .member("shifts", s.neighbourList.shifts)
        .endObject();
    auto const conserved = [&w](char const* key, RunSummary::Conserved const& c) {
        w.key(key)
            .beginObject()
            .member("momentum", c.momentum)
            .member("angular_momentum", c.angularMomentum)
            .member("kinetic_energy", c.kineticEnergy)
            .member("rotational_kinetic_energy", c.rotationalEnergy)
            .member("potential_energy", c.potentialEnergy)
            .member("center_of_mass", c.centerOfMass)
            .member("mass", c.mass)
            .endObject();
    };
    conserved("conserved", s.conserved);
    conserved("conserved_initial", s.initialConserved);
    w.key("walls").beginArray();
    for (RunSummary::Wall const& wall : s.walls)
        w.beginObject()
            .member("force", wall.force)
            .member("torque", wall.torque)
            .member("work", wall.work)
            .endObject();
    w.endArray();
    w.member("checksum", s.checksum).endObject();
    return w.str();
}

std::uint64_t peakRssBytes(core::Comm const& comm) {
    rusage usage{};
    unsigned long bytes = 0;
    if (getrusage(RUSAGE_SELF, &usage) == 0 && usage.ru_maxrss > 0)
        bytes = static_cast<unsigned long>(usage.ru_maxrss) * 1024UL;
    return comm.allReduce(bytes, core::ReduceOp::Max);
}

} // namespace regolith::apps
