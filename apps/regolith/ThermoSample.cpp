#include "apps/regolith/ThermoSample.hpp"

#include "apps/common/ConservedQuantities.hpp"
#include "apps/regolith/LoopSummary.hpp"
#include "apps/regolith/WallLoads.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace regolith::apps {

namespace {

/// The contacts in `contacts` and their largest overlap relative to the smaller radius. Not
/// collective.
std::pair<std::int64_t, double> contactsAndOverlap(particles::LocalParticles const& local,
                                                   std::span<particles::ContactList const> lists) {
    auto const blocks = local.blocks();
    std::int64_t count = 0;
    double overlap = 0.0;
    for (std::size_t b = 0; b < blocks.size() && b < lists.size(); ++b) {
        particles::ParticleStorage const& ps = blocks[b].particles;
        count += static_cast<std::int64_t>(lists[b].size());
        for (particles::Contact const& c : lists[b].pairs)
            overlap = std::max(overlap, c.penetration / std::min(ps.radius(c.i), ps.radius(c.j)));
        for (particles::WallContact const& c : lists[b].walls)
            overlap = std::max(overlap, c.penetration / ps.radius(c.particle));
    }
    return {count, overlap};
}

} // namespace

ThermoSample measureThermo(core::Comm const& comm, particles::LocalParticles const& local,
                           std::span<particles::ContactList const> contacts,
                           ThermoContext const& context) {
    RunSummary::Conserved const c =
        conservedQuantitiesFrom(comm, masterSource(local), context.gravity);
    auto const [count, overlap] = contactsAndOverlap(local, contacts);
    std::array<long long, 2> counts{static_cast<long long>(count),
                                    static_cast<long long>(local.countMasters())};
    comm.allReduceInPlace(std::span<long long>(counts), core::ReduceOp::Sum);
    ThermoSample s;
    s.step = context.step;
    s.time = context.time;
    s.translationalEnergy = c.kineticEnergy - c.rotationalEnergy;
    s.rotationalEnergy = c.rotationalEnergy;
    s.externalPotential = c.potentialEnergy;
    s.selfPotential = context.selfPotential;
    s.momentum = c.momentum;
    s.angularMomentum = c.angularMomentum;
    s.contacts = counts[0];
    s.maxOverlap = comm.allReduce(overlap, core::ReduceOp::Max);
    s.grains = counts[1];
    s.imbalance = context.imbalance;
    if (context.walls != nullptr)
        for (RunSummary::Wall const& w : reduceWallLoads(comm, *context.walls))
            s.wallForces.push_back(w.force);
    return s;
}

std::vector<ThermoColumn> thermoColumns(std::size_t walls) {
    using S = ThermoSample const&;
    std::vector<ThermoColumn> columns{
        ThermoColumn{"step", "steps done", true, [](S s) { return double(s.step); }},
        ThermoColumn{"time", "simulated time", false, [](S s) { return s.time; }},
        ThermoColumn{"ke_trans", "translational kinetic energy, sum 1/2 m |v|^2", false,
                     [](S s) { return s.translationalEnergy; }},
        ThermoColumn{"ke_rot", "rotational kinetic energy, sum 1/2 I |w|^2 (I = 2/5 m r^2)", false,
                     [](S s) { return s.rotationalEnergy; }},
        ThermoColumn{"pe_external", "potential energy in gravity.external, sum -m g.x", false,
                     [](S s) { return s.externalPotential; }},
        ThermoColumn{"pe_self", "self-gravity energy 1/2 sum m phi of the last field computed",
                     false, [](S s) { return s.selfPotential; }},
        ThermoColumn{"px", "momentum sum m v, x", false, [](S s) { return s.momentum.x(); }},
        ThermoColumn{"py", "momentum, y", false, [](S s) { return s.momentum.y(); }},
        ThermoColumn{"pz", "momentum, z", false, [](S s) { return s.momentum.z(); }},
        ThermoColumn{"lx", "angular momentum about the origin, sum (x cross m v + I w), x", false,
                     [](S s) { return s.angularMomentum.x(); }},
        ThermoColumn{"ly", "angular momentum, y", false, [](S s) { return s.angularMomentum.y(); }},
        ThermoColumn{"lz", "angular momentum, z", false, [](S s) { return s.angularMomentum.z(); }},
        ThermoColumn{"contacts", "grain-grain and grain-wall contacts", true,
                     [](S s) { return double(s.contacts); }},
        ThermoColumn{"max_overlap", "largest overlap / smaller radius of any contact", false,
                     [](S s) { return s.maxOverlap; }},
        ThermoColumn{"grains", "grains in the domain", true, [](S s) { return double(s.grains); }},
        ThermoColumn{"imbalance", "the ranks' last measured load imbalance, max / mean", false,
                     [](S s) { return s.imbalance; }},
    };
    for (std::size_t k = 0; k < walls; ++k)
        for (int a = 0; a < 3; ++a)
            columns.push_back(
                {fmt::format("wall{}_f{}", k, "xyz"[a]),
                 fmt::format("force of the grains on wall {} ([[walls]] order), {}", k, "xyz"[a]),
                 false,
                 [k, a](S s) { return k < s.wallForces.size() ? s.wallForces[k][a] : 0.0; }});
    return columns;
}

} // namespace regolith::apps
