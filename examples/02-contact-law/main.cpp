// Tutorial 02: a contact law of one's own -- Hertz elasticity with DMT adhesion, the whole law
// in HertzDmtLaw.hpp -- registered with one line, chosen by name as a scene would, and its
// pull-off force measured against the closed form.
//
// Two grains stick; one is fixed, the other is pulled away by a slowly growing force of our
// own; they part when the pull exceeds the adhesion, at F = 2 pi w R* (the DMT pull-off
// force). Run: ./02-contact-law [steps].
#include "core/config/ConfigTable.hpp"
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "HertzDmtLaw.hpp"

using namespace regolith;
using core::Vec3;

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    long long const steps = argc > 1 ? std::atoll(argv[1]) : 20000;

    particles::contactModels().add(tutorial::hertzDmtEntry()); // the registration line

    // The [contact] table of a scene that names the law (here from a string).
    auto const contact = core::ConfigTable::fromString(
        "model = \"hertz-dmt\"\neffective_modulus = 1.0e4\nadhesion_work = 1.0\n"
        "damping_ratio = 0.5\n",
        "02-contact-law");
    coupling::SimulationSetup setup;
    setup.domain.domain = core::AABB{Vec3::Constant(-4.0), Vec3::Constant(4.0)};
    setup.domain.rootBlocks = {2, 2, 2};
    setup.contact = particles::contactModelEntry(contact).make({contact, {}, {}});
    tutorial::HertzDmtLaw const* law = setup.contact->get<tutorial::HertzDmtLaw>();
    if (law == nullptr)
        return 1;
    setup.dem.dt = 2e-3;
    coupling::Simulation sim(world, setup);

    // Two grains of radius 0.5 stuck together at the origin, at rest (the overlap where the
    // Hertz force balances the adhesion: a contact exists only while the grains overlap); the
    // left one held in place.
    double const mass = 4.0 / 3.0 * std::numbers::pi * 0.125;
    double const overlap = law->restingOverlap(0.25);
    double const fixedAt = -(0.5 - 0.5 * overlap);
    for (int side : {-1, 1}) {
        particles::ParticleInit p;
        p.uid = side < 0 ? 0 : 1;
        p.position = Vec3((0.5 - 0.5 * overlap) * side, 0.0, 0.0);
        p.radius = 0.5;
        p.mass = mass;
        if (side < 0)
            p.flags = particles::Flag::Fixed;
        sim.addGrain(p);
    }

    // Our force: on grain 1, along +x, growing linearly to 1.5x the pull-off over the run.
    double const pullOff = law->pullOff(0.25);
    double const rate = 1.5 * pullOff / (static_cast<double>(steps) * setup.dem.dt);
    sim.addBodyForces([&](particles::LocalParticles& grains) {
        for (particles::BlockParticles& block : grains.blocks())
            block.particles.forEachMaster([&](std::size_t i) {
                if (block.particles.uid(i) == 1)
                    block.particles.force(i).x() += rate * sim.time();
            });
    });
    // Our observer: the pull when the grains parted (their gap opened), every step.
    double parted = 0.0;
    sim.addObserver(1, [&](coupling::Simulation& s) {
        double x = 0.0;
        s.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
            if (g.uid(i) == 1)
                x = g.position(i).x();
        });
        x = s.comm().allReduce(x, core::ReduceOp::Sum);
        if (parted == 0.0 && x - fixedAt > 1.0) // centres a diameter apart: no overlap left
            parted = rate * s.time();
    });
    sim.start();
    sim.run(steps);

    double const error = std::abs(parted - pullOff) / pullOff;
    if (world.rank() == 0)
        std::printf("pull-off force: measured %.5f, DMT 2 pi w R* = %.5f (%.2f %% apart)\n", parted,
                    pullOff, 100.0 * error);
    return error < 0.01 ? 0 : 1;
}
