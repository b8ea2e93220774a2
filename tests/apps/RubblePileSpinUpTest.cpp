// Validation of the spin-up (docs/guide/rubble-piles.md): a cohesionless, self-gravitating
// pile of 268 grains on a cubic lattice, spun up slowly by the spin-up torque, fails when its
// spin reaches the orbital rate at its surface, omega_c = sqrt(4 pi G rho_bulk / 3), rho_bulk
// the bulk density of the equivalent ellipsoid (PileMeasures): its spin peaks within 10 % of
// omega_c, then it flattens and sheds mass from its equator. With van der Waals cohesion the
// same pile holds well above the spin at which the cohesionless one fails.
#include "apps/spin_up/PileRecorder.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "particles/kernels/VanDerWaals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

using namespace regolith;
using core::Vec3;

namespace {

constexpr double kGrainRadius = 0.5;

core::Comm const& world() {
    static core::Comm const comm(MPI_COMM_WORLD);
    return comm;
}

/// Frictional spring-dashpot contacts (overlap ~1 % of a radius at rest).
particles::SpringDashpot frictionalContacts() {
    particles::LinearContactParams contact;
    contact.stiffness = 2.0e3;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.5;
    contact.friction = 0.5;
    return particles::SpringDashpot(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));
}

/// A ball of n lattice sites per diameter (grains of diameter 1 on a cubic lattice),
/// turning at `spin` about z, in a box of 4 radii with 4^3 blocks, direct gravity (G = 1).
coupling::SimulationSetup pileSetup(int n, particles::AnyContactModel contact) {
    double const box = 2.0 * n;
    coupling::SimulationSetup setup;
    setup.domain.domain = core::AABB{Vec3::Constant(-box), Vec3::Constant(box)};
    setup.domain.rootBlocks = {4, 4, 4};
    setup.sync.reproducible = true;
    setup.contact = std::move(contact);
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

struct SpinUpRun {
    double rate = 0.02;      ///< d omega / dt [omega_c^2]
    double startSpin = 1.17; ///< the lattice ball of n = 9 has omega_c = 1.468 (G = 1)
    double finalSpin = 1.2;  ///< [omega_c]
    std::int64_t steps = 10000;
    std::string name = "rubble_pile_test";
};

/// Spins the ball up from `run.startSpin` at `run.rate`; records every 200 steps.
SpinUpOutcome spinUp(int n, particles::AnyContactModel contact, SpinUpRun const& run) {
    coupling::SimulationSetup const setup = pileSetup(n, std::move(contact));
    apps::RubblePileScene scene;
    // One file per rank count: the runs of this test on several rank counts may run at once.
    scene.pile.file = run.name + "_np" + std::to_string(world().size()) + ".csv";
    scene.pile.recordEvery = 200;
    scene.pile.radius = 1.5;
    apps::SpinUpSection spin;
    spin.rate = run.rate;
    spin.finalSpin = run.finalSpin;
    scene.spinUp = spin;
    coupling::Simulation sim(world(), setup);
    addBall(sim, n, run.startSpin);
    apps::PileRecorder recorder(world(), scene, 1.0, setup.dem.dt);
    SpinUpOutcome out;
    sim.addBodyForces([&](particles::LocalParticles& g) { recorder.addForces(g); });
    sim.addObserver(recorder.recordEvery(), [&](coupling::Simulation& s) {
        out.last = recorder.record(s.grains()).value();
    });
    sim.start();
    sim.run(run.steps);
    out.omegaC = recorder.reference().omegaC;
    out.failure = recorder.failureSpin().value_or(0.0);
    out.onset = recorder.sheddingOnset().value_or(0.0);
    return out;
}

} // namespace

TEST(SpinUpValidation, CohesionlessPileFailsAtTheCriticalSpinThenSheds) {
    SpinUpOutcome const r = spinUp(9, frictionalContacts(), SpinUpRun{});
    if (world().rank() == 0)
        std::printf("omega_c %.4f, fails at %.3f omega_c, sheds from %.3f omega_c, shed %.3f, "
                    "remnant %.3f\n",
                    r.omegaC, r.failure, r.onset, r.last.shedFraction, r.last.remnantFraction);
    EXPECT_GT(r.failure, 0.9);
    EXPECT_LT(r.failure, 1.1);
    EXPECT_GT(r.last.shedFraction, 0.0); // and then sheds
}

// The same ball spun up faster (0.05 omega_c^2 from 0.85 omega_c), without and with van der
// Waals cohesion of a pull-off force F_c = A R* / (6 s_min^2) = 4 per contact, 0.8 times the
// weight of a surface grain (m g = m omega_c^2 R = 5.1): a surface grain bound by one contact
// lifts off only at omega^2 = omega_c^2 + F_c / (m R), 1.3 omega_c. The cohesive pile must
// still turn, unbroken, 0.15 omega_c above the spin at which the cohesionless one failed.
TEST(SpinUpValidation, CohesivePileHoldsAboveTheCohesionlessFailure) {
    SpinUpRun run{.rate = 0.05,
                  .startSpin = 0.85 * 1.468,
                  .finalSpin = 1.3,
                  .steps = 3000,
                  .name = "rubble_pile_cohesionless"};
    SpinUpOutcome const dry = spinUp(9, frictionalContacts(), run);
    // F_c = A R* / (6 s_min^2) with R* = 0.25 for two grains of radius 0.5.
    particles::VanDerWaalsParams const vdw{
        .hamaker = 4.0 * 6.0 * 0.01 * 0.01 / 0.25, .minSeparation = 0.01, .cutoff = 0.05};
    run.steps = 4500;
    run.name = "rubble_pile_cohesive";
    SpinUpOutcome const wet = spinUp(9, particles::VanDerWaals(frictionalContacts(), vdw), run);
    double const wetSpin = wet.last.spin / wet.omegaC;
    if (world().rank() == 0)
        std::printf("cohesionless: fails at %.3f omega_c; cohesive: %s %.3f omega_c, shed %.3f\n",
                    dry.failure, wet.failure > 0.0 ? "fails at" : "holds at",
                    wet.failure > 0.0 ? wet.failure : wetSpin, wet.last.shedFraction);
    ASSERT_GT(dry.failure, 0.0) << "the cohesionless pile did not fail";
    EXPECT_LT(dry.failure, 1.05);
    EXPECT_EQ(wet.failure, 0.0) << "the cohesive pile failed at " << wet.failure << " omega_c";
    EXPECT_GT(wetSpin, dry.failure + 0.15);
    EXPECT_EQ(wet.last.shedFraction, 0.0);
}
