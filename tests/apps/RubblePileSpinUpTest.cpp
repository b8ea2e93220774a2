// Validation of the spin-up (docs/guide/rubble-piles.md): a cohesionless, self-gravitating
// pile of 268 grains on a cubic lattice, spun up slowly by the spin-up torque, fails when its
// spin reaches the orbital rate at its surface, omega_c = sqrt(4 pi G rho_bulk / 3), rho_bulk
// the bulk density of the equivalent ellipsoid (PileMeasures): its spin peaks within 10 % of
// omega_c, then it flattens and sheds mass from its equator. Run on 1 and 4 ranks.
#include "apps/spin_up/PileRecorder.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>

using namespace regolith;
using core::Vec3;

namespace {

constexpr double kGrainRadius = 0.5;

core::Comm const& world() {
    static core::Comm const comm(MPI_COMM_WORLD);
    return comm;
}

/// A ball of n lattice sites per diameter (grains of diameter 1 on a cubic lattice),
/// turning at `spin` about z, in a box of 4 radii with 4^3 blocks, direct gravity (G = 1),
/// frictional spring-dashpot contacts (overlap ~1 % of a radius at rest).
coupling::SimulationSetup pileSetup(int n) {
    double const box = 2.0 * n;
    coupling::SimulationSetup setup;
    setup.domain.domain = core::AABB{Vec3::Constant(-box), Vec3::Constant(box)};
    setup.domain.rootBlocks = {4, 4, 4};
    setup.sync.reproducible = true;
    particles::LinearContactParams contact;
    contact.stiffness = 2.0e3;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.5;
    contact.friction = 0.5;
    setup.contact = particles::SpringDashpot(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));
    setup.dem.dt = 1e-3; // t_c / 25
    coupling::SelfGravityConfig gravity;
    gravity.method = "direct"; // the same bits on any ranks
    gravity.G = 1.0;
    gravity.softening = kGrainRadius;
    gravity.reproducible = true;
    setup.selfGravity = gravity;
    return setup;
}

void addBall(coupling::Simulation& sim, int n, double spin) {
    double const R = 0.5 * n;
    particles::Uid uid = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                Vec3 const x(i - 0.5 * (n - 1), j - 0.5 * (n - 1), k - 0.5 * (n - 1));
                if (x.norm() > R - kGrainRadius)
                    continue;
                particles::ParticleInit p;
                p.uid = uid++;
                p.position = x;
                p.velocity = spin * Vec3::UnitZ().cross(x);
                p.angularVelocity = spin * Vec3::UnitZ();
                p.radius = kGrainRadius;
                p.mass = 4.0 / 3.0 * std::numbers::pi * std::pow(kGrainRadius, 3);
                sim.addGrain(p);
            }
}

struct SpinUpOutcome {
    double omegaC = 0.0;
    double failure = 0.0;  ///< the peak spin / omega_c, once passed
    double onset = 0.0;    ///< spin / omega_c at the first record with mass shed
    apps::PileRecord last; ///< at the end
};

/// Spins the ball up from 0.8 omega_c at `rate` omega_c^2 to 1.2 omega_c; records every 200
/// steps.
SpinUpOutcome spinUp(int n, double rate, std::int64_t steps) {
    coupling::SimulationSetup const setup = pileSetup(n);
    apps::RubblePileScene scene;
    // One file per rank count: the np1 and np4 runs of this test may run at once.
    scene.pile.file = "rubble_pile_test_np" + std::to_string(world().size()) + ".csv";
    scene.pile.recordEvery = 200;
    scene.pile.radius = 1.5;
    apps::SpinUpSection spin;
    spin.rate = rate;
    spin.finalSpin = 1.2;
    scene.spinUp = spin;
    coupling::Simulation sim(world(), setup);
    // The lattice ball of n = 9 has omega_c = 1.468 (G = 1): 0.8 omega_c = 1.17.
    addBall(sim, n, 1.17);
    apps::PileRecorder recorder(world(), scene, 1.0, setup.dem.dt);
    SpinUpOutcome out;
    sim.addBodyForces([&](particles::LocalParticles& g) { recorder.addForces(g); });
    sim.addObserver(recorder.recordEvery(), [&](coupling::Simulation& s) {
        out.last = recorder.record(s.grains()).value();
    });
    sim.start();
    sim.run(steps);
    out.omegaC = recorder.reference().omegaC;
    out.failure = recorder.failureSpin().value_or(0.0);
    out.onset = recorder.sheddingOnset().value_or(0.0);
    return out;
}

} // namespace

TEST(SpinUpValidation, CohesionlessPileFailsAtTheCriticalSpinThenSheds) {
    SpinUpOutcome const r = spinUp(9, 0.02, 10000);
    if (world().rank() == 0)
        std::printf("omega_c %.4f, fails at %.3f omega_c, sheds from %.3f omega_c, shed %.3f, "
                    "remnant %.3f\n",
                    r.omegaC, r.failure, r.onset, r.last.shedFraction, r.last.remnantFraction);
    EXPECT_GT(r.failure, 0.9);
    EXPECT_LT(r.failure, 1.1);
    EXPECT_GT(r.last.shedFraction, 0.0); // and then sheds
}
