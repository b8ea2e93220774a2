// Tutorial 01: a granular gas set up in C++, without a scene file.
//
// 4,096 grains on a cubic lattice in a periodic box cut into 4 x 4 x 4 blocks, given random
// velocities, collide inelastically: the kinetic energy decays (Haff's law). The program sets up
// in code what a scene file says to the `regolith` driver (coupling::Simulation: the forest, the
// grains, the contact law, the step) and prints the energy every 100 steps with an observer of
// its own. Run: mpiexec -n 2 ./01-granular-gas [steps].
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/random/CounterRng.hpp"
#include "coupling/simulation/Simulation.hpp"

#include <cstdio>
#include <cstdlib>
#include <numbers>

using namespace regolith;
using core::Vec3;

namespace {

constexpr int kGrainsPerAxis = 16;  // 16^3 grains, one per unit cell
constexpr double kRadius = 0.4;     // [length]; the scene is unit-free
constexpr double kDensity = 1.0;    // [mass/length^3]
constexpr std::uint64_t kSeed = 42; // velocities depend on (seed, uid) only, not on ranks

/// The translational kinetic energy of all grains on all ranks. COLLECTIVE.
double kineticEnergy(coupling::Simulation& sim) {
    double e = 0.0;
    sim.forEachGrain([&](particles::ParticleStorage const& grains, std::size_t i) {
        e += 0.5 * grains.mass(i) * grains.velocity(i).squaredNorm();
    });
    return sim.comm().allReduce(e, core::ReduceOp::Sum);
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    int const steps = argc > 1 ? std::atoi(argv[1]) : 1000;

    coupling::SimulationSetup setup;
    // The domain: a periodic box cut into 4 x 4 x 4 blocks. Each rank gets a stretch of them
    // along a Hilbert curve, by the load of the grains in them.
    setup.domain.domain = core::AABB{Vec3::Zero(), Vec3::Constant(kGrainsPerAxis)};
    setup.domain.rootBlocks = {4, 4, 4};
    setup.domain.periodic = {true, true, true};
    // The contact law: a linear spring-dashpot with Coulomb friction (Cundall & Strack 1979),
    // one row of material parameters (grain type 0).
    particles::LinearContactParams contact;
    contact.stiffness = 1000.0;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.8;
    contact.friction = 0.3;
    setup.contact = particles::SpringDashpot(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));
    setup.dem.dt = 0.002; // a twentieth of the contact time pi sqrt(m / 2k)
    coupling::Simulation sim(world, setup);

    // The grains, given alike on every rank (each keeps those in its blocks). A grain's
    // velocity comes from a random stream keyed by its uid, so the gas is the same on any
    // number of ranks.
    double const mass = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius * kDensity;
    particles::Uid uid = 0;
    for (int i = 0; i < kGrainsPerAxis; ++i)
        for (int j = 0; j < kGrainsPerAxis; ++j)
            for (int k = 0; k < kGrainsPerAxis; ++k, ++uid) {
                core::random::CounterRng rng(kSeed, uid);
                particles::ParticleInit p;
                p.uid = uid;
                p.position = Vec3(i + 0.5, j + 0.5, k + 0.5);
                p.velocity = Vec3(rng.normal(), rng.normal(), rng.normal());
                p.radius = kRadius;
                p.mass = mass;
                sim.addGrain(p);
            }

    // Our own output: the kinetic energy every 100 steps.
    double e0 = 0.0;
    sim.addObserver(100, [&](coupling::Simulation& s) {
        double const e = kineticEnergy(s);
        if (world.rank() == 0)
            std::printf("step %5lld  t %6.3f  E_kin / E_kin(0) %.4f\n",
                        static_cast<long long>(s.stepsDone()), s.time(), e / e0);
    });
    sim.start(); // shadows and the initial forces
    e0 = kineticEnergy(sim);
    sim.run(steps);

    // Every grain is still there, and the gas cooled: inelastic collisions took energy.
    double const e = kineticEnergy(sim);
    auto const grains = world.allReduce(sim.grains().countMasters(), core::ReduceOp::Sum);
    if (world.rank() == 0)
        std::printf("grains %zu, energy left %.4f\n", grains, e / e0);
    return grains == kGrainsPerAxis * kGrainsPerAxis * kGrainsPerAxis && e < e0 ? 0 : 1;
}
