// Tutorial 01: a granular gas set up in C++, without a scene file.
//
// 4,096 grains on a cubic lattice in a periodic box cut into 4 x 4 x 4 blocks, given random
// velocities, collide inelastically: the kinetic energy decays (Haff's law). The program builds
// what the `regolith` driver builds from a scene (forest, particles, synchronisation, DEM step)
// and prints the energy every 100 steps. Run: mpiexec -n 2 ./01-granular-gas [steps].
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/random/CounterRng.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/simulation/DemStep.hpp"

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
double kineticEnergy(core::Comm const& comm, particles::LocalParticles const& local) {
    double e = 0.0;
    for (particles::BlockParticles const& block : local.blocks())
        block.particles.forEachMaster([&](std::size_t i) {
            e += 0.5 * block.particles.mass(i) * block.particles.velocity(i).squaredNorm();
        });
    return comm.allReduce(e, core::ReduceOp::Sum);
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    int const steps = argc > 1 ? std::atoi(argv[1]) : 1000;

    // The domain and its blocks: each rank gets a share of the 64 blocks (a Hilbert-curve cut).
    domain::ForestSpec spec;
    spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(kGrainsPerAxis)};
    spec.rootBlocks = {4, 4, 4};
    spec.periodic = {true, true, true};
    domain::BlockForest const forest(world, spec);

    // The grains: every rank offers every grain; addMaster keeps those in its own blocks.
    particles::LocalParticles local(forest);
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
                (void)local.addMaster(p);
            }

    // The contact law: a linear spring-dashpot with Coulomb friction (Cundall & Strack 1979),
    // stiff enough that grains at speed 3 overlap by ~2 % of their radius.
    particles::LinearContactParams contact;
    contact.stiffness = 1000.0;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.8;
    contact.friction = 0.3;
    particles::SpringDashpot model(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));

    // The step: NNS/SOS synchronisation (hybrid), velocity Verlet, no walls, no gravity.
    particles::ParticleSync sync(world, forest, particles::SyncConfig{});
    core::TimerTree timers;
    particles::DemStepConfig config;
    config.dt = 0.002; // a twentieth of the contact time pi sqrt(m / 2k)
    config.keepContacts = false;
    particles::DemStep dem(world, sync, local, model, particles::VelocityVerlet{},
                           particles::WallList{}, config, timers);
    dem.setUp();

    double const e0 = kineticEnergy(world, local);
    for (int n = 1; n <= steps; ++n) {
        dem.step();
        if (n % 100 == 0 || n == steps) {
            double const e = kineticEnergy(world, local);
            if (world.rank() == 0)
                std::printf("step %5d  t %6.3f  E_kin / E_kin(0) %.4f\n", n, n * config.dt, e / e0);
        }
    }
    dem.completeStep();
    // Every grain is still there, and the gas cooled: inelastic collisions took energy.
    double const e = kineticEnergy(world, local);
    auto const grains = world.allReduce(local.countMasters(), core::ReduceOp::Sum);
    if (world.rank() == 0)
        std::printf("grains %zu, energy left %.4f\n", grains, e / e0);
    return grains == kGrainsPerAxis * kGrainsPerAxis * kGrainsPerAxis && e < e0 ? 0 : 1;
}
