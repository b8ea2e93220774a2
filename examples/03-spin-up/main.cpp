// Tutorial 03: a self-gravitating rubble pile spun up by an external torque until it sheds mass.
//
// A ball of grains held together by its own gravity (Barnes-Hut) and by contacts is given a
// uniform angular acceleration about z by a body force of our own, f_i = m_i alpha z x x_i.
// A cohesionless pile sheds grains from its equator once the centrifugal acceleration there
// exceeds gravity's: at omega_c = sqrt(4 pi G rho_bulk / 3) for a sphere of bulk density
// rho_bulk. An observer of our own records the spin rate, the mass shed and the pile's
// equatorial radius to spin_up.csv. Run: mpiexec -n 2 ./03-spin-up [sites per diameter] [steps].
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

using namespace regolith;
using core::Vec3;

namespace {

constexpr double kRadius = 0.5; // grains of diameter 1 on a cubic lattice of spacing 1
constexpr double kDensity = 1.0;
constexpr double kG = 1.0; // units in which the pile's free-fall time is of order one

/// What the observer measures, summed over the ranks.
struct PileState {
    double mass = 0.0;        ///< all grains
    double spin = 0.0;        ///< L_z / I_z about the centre of mass [rad/time]
    double shedMass = 0.0;    ///< grains farther than `shedRadius` from the centre
    double equatorRadius = 0; ///< the farthest grain within shedRadius, in the plane z ~ c_z
};

PileState measure(coupling::Simulation& sim, double shedRadius) {
    // Centre of mass first (one reduction), then the moments about it (another).
    double sums[4] = {0, 0, 0, 0};
    sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        sums[0] += g.mass(i);
        for (int d = 0; d < 3; ++d)
            sums[1 + d] += g.mass(i) * g.position(i)[d];
    });
    sim.comm().allReduceInPlace(std::span<double>(sums), core::ReduceOp::Sum);
    Vec3 const c = Vec3(sums[1], sums[2], sums[3]) / sums[0];
    double moments[3] = {0, 0, 0}; // L_z, I_z, shed mass
    double farthest = 0.0;
    sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        Vec3 const r = g.position(i) - c;
        double const axis2 = r.x() * r.x() + r.y() * r.y();
        moments[0] += g.mass(i) * (r.x() * g.velocity(i).y() - r.y() * g.velocity(i).x());
        moments[1] += g.mass(i) * axis2;
        if (r.norm() > shedRadius)
            moments[2] += g.mass(i);
        else if (std::abs(r.z()) < 1.0)
            farthest = std::max(farthest, std::sqrt(axis2));
    });
    sim.comm().allReduceInPlace(std::span<double>(moments), core::ReduceOp::Sum);
    return {sums[0], moments[0] / moments[1], moments[2],
            sim.comm().allReduce(farthest, core::ReduceOp::Max)};
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    core::Comm const world;
    int const n = argc > 1 ? std::atoi(argv[1]) : 12; // lattice sites per diameter
    long long const steps = argc > 2 ? std::atoll(argv[2]) : 20000;

    // The pile: the sites of a cubic lattice inside a sphere of radius R, in a box with room
    // around it for what it sheds (grains leaving the box are dropped, and counted as shed).
    double const R = 0.5 * n;
    double const box = 4.0 * R;
    coupling::SimulationSetup setup;
    setup.domain.domain = core::AABB{Vec3::Constant(-box), Vec3::Constant(box)};
    setup.domain.rootBlocks = {4, 4, 4};
    particles::LinearContactParams contact; // stiff: overlaps ~1 % of a radius at rest
    contact.stiffness = 2.0e3;
    contact.tangentialStiffness = 2.0 / 7.0 * contact.stiffness;
    contact.restitution = 0.5;
    contact.friction = 0.5;
    setup.contact = particles::SpringDashpot(
        particles::MaterialTable<particles::LinearContactParams>(1, contact));
    setup.dem.dt = 1e-3; // t_c / 25
    coupling::SelfGravityConfig gravity;
    gravity.method = "tree";
    gravity.G = kG;
    gravity.theta = 0.5;
    gravity.softening = kRadius;
    setup.selfGravity = gravity;
    coupling::Simulation sim(world, setup);

    double const grainMass = 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kDensity;
    particles::Uid uid = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                Vec3 const x(i - 0.5 * (n - 1), j - 0.5 * (n - 1), k - 0.5 * (n - 1));
                if (x.norm() > R - kRadius)
                    continue;
                particles::ParticleInit p;
                p.uid = uid++;
                p.position = x;
                p.radius = kRadius;
                p.mass = grainMass;
                sim.addGrain(p);
            }
    double const pileMass = static_cast<double>(uid) * grainMass;

    // Our body force: a uniform angular acceleration about the z axis through the origin
    // (the pile's centre), alpha until the spin-up ends, then none.
    double alpha = 0.0;
    sim.addBodyForces([&alpha](particles::LocalParticles& grains) {
        for (particles::BlockParticles& block : grains.blocks())
            block.particles.forEachMaster([&](std::size_t i) {
                auto& g = block.particles;
                Vec3 const r = g.position(i);
                g.force(i) += g.mass(i) * alpha * Vec3(-r.y(), r.x(), 0.0);
            });
    });
    sim.start();

    // The critical spin: the equator's orbital rate, omega_c = sqrt(G M / a^3) for a pile of
    // mass M and equatorial radius a (the outer edge of its equatorial grains), which is
    // sqrt(4 pi G rho_bulk / 3) for a sphere of bulk density rho_bulk.
    double const a = measure(sim, box).equatorRadius + kRadius;
    double const omegaC = std::sqrt(kG * pileMass / (a * a * a));
    // Spun up from rest to 1.3 omega_c over 80 % of the run (slowly against the pile's
    // dynamical time 1 / omega_c), then left to shed.
    long long const spinUpSteps = steps * 4 / 5;
    alpha = 1.3 * omegaC / (static_cast<double>(spinUpSteps) * setup.dem.dt);

    // Our output: spin rate, mass shed and equatorial radius every 1 % of the run. Lift-off:
    // the equator grew by a grain radius.
    std::FILE* csv = world.rank() == 0 ? std::fopen("spin_up.csv", "w") : nullptr;
    if (csv)
        std::fprintf(csv, "time,omega,omega_over_omega_c,shed_fraction,equator_radius\n");
    double liftOff = 0.0; // omega / omega_c then
    sim.addObserver(std::max(1LL, steps / 100), [&](coupling::Simulation& s) {
        if (s.stepsDone() >= spinUpSteps)
            alpha = 0.0;
        PileState const p = measure(s, a + 4.0 * kRadius);
        double const shed =
            std::max(0.0, 1.0 - (p.mass - p.shedMass) / pileMass); // left the box: shed too
        if (liftOff == 0.0 && p.equatorRadius > a) // a grain centre where the edge was
            liftOff = p.spin / omegaC;
        if (csv) {
            std::fprintf(csv, "%.6g,%.6g,%.6g,%.6g,%.6g\n", s.time(), p.spin, p.spin / omegaC, shed,
                         p.equatorRadius + kRadius);
            std::fflush(csv); // a long run can be watched
        }
    });
    if (world.rank() == 0)
        std::printf("%lld grains, equatorial radius %.2f, omega_c %.4f; spinning up to 1.3 "
                    "omega_c in %lld steps\n",
                    static_cast<long long>(uid), a, omegaC, spinUpSteps);
    sim.run(steps);
    if (csv)
        std::fclose(csv);
    PileState const end = measure(sim, a + 4.0 * kRadius);
    double const shed = std::max(0.0, 1.0 - (end.mass - end.shedMass) / pileMass);
    if (world.rank() == 0)
        std::printf("the equator lifted off at omega = %.3f omega_c; %.1f %% of the mass shed\n",
                    liftOff, 100.0 * shed);
    // A cohesionless pile lifts off near omega_c, and sheds once spun past it.
    bool const expected = liftOff > 0.8 && liftOff < 1.2 && shed > 0.0;
    return expected ? 0 : 1;
}
