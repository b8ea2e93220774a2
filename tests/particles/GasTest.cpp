// An elastic granular gas in a closed box: total energy (kinetic + elastic overlap energy)
// is conserved by velocity Verlet.
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace regolith::particles;
using namespace regolith::particles::test;

TEST(ElasticGas, EnergyDriftBelow1e4Over10000Steps) {
    constexpr double kBox = 8.0;
    constexpr double kDensity = 1.0;
    LinearContactParams p;
    p.stiffness = 100.0;
    p.tangentialStiffness = 0.0;
    p.restitution = 1.0;
    p.friction = 0.0;
    SpringDashpot const model{MaterialTable<LinearContactParams>(1, p)};

    WallList walls;
    for (int d = 0; d < 3; ++d) {
        walls.add(Vec3::Zero(), Vec3::Unit(d));
        walls.add(Vec3::Constant(kBox), -Vec3::Unit(d));
    }
    // 216 polydisperse spheres on a jittered 6^3 lattice (no initial overlap), random
    // velocities in [-1, 1]^3.
    ParticleStorage ps;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double const spacing = kBox / 6.0;
    Uid uid = 1;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k) {
                double const r = 0.2 + 0.15 * u(rng);
                Vec3 x = (Vec3(i, j, k) + Vec3::Constant(0.5)) * spacing;
                x += 0.1 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
                Vec3 const v(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
                ps.add(sphere(uid++, x, r, sphereMass(r, kDensity), v));
            }

    // dt = t_c / 50 for the lightest pair (the guard's t_c / 10 limit, five times finer).
    double const mMin = sphereMass(0.2, kDensity);
    double const dt = SpringDashpot::contactTime(p, mMin / 2) / 50.0;
    BlockStepper stepper(ps, walls, model, VelocityVerlet{}, dt);
    auto energy = [&] {
        double e = 0.0;
        for (std::size_t i = 0; i < ps.size(); ++i)
            e += 0.5 * ps.mass(i) * ps.velocity(i).squaredNorm() +
                 0.5 * ps.angularVelocity(i).squaredNorm() / ps.invInertia(i);
        return e + elasticEnergy(ps, walls, stepper.contacts(),
                                 [&](std::uint32_t, std::uint32_t) { return p.stiffness; });
    };
    double const e0 = energy();
    std::size_t pairContacts = 0, wallContacts = 0;
    double worst = 0.0;
    for (int n = 0; n < 10000; ++n) {
        stepper.step();
        pairContacts += stepper.contacts().pairs.size();
        wallContacts += stepper.contacts().walls.size();
        if (n % 10 == 0)
            worst = std::max(worst, std::abs(energy() - e0) / e0);
    }
    // The gas did collide, with each other and with the walls (counts in contact-steps; one
    // collision lasts ~50 steps).
    EXPECT_GT(pairContacts, 50U * 100U);
    EXPECT_GT(wallContacts, 50U * 100U);
    // Relative drift below 1e-4 (the bound), and the worst excursion (sampled every
    // 10 steps) too.
    EXPECT_LT(std::abs(energy() - e0) / e0, 1e-4);
    EXPECT_LT(worst, 1e-4);
    // Everyone stayed in the box.
    for (std::size_t i = 0; i < ps.size(); ++i)
        EXPECT_TRUE((ps.position(i).array() > 0.0).all() && (ps.position(i).array() < kBox).all());
}
