// Integrators, the rotation update, contact evaluation on shadows, and the tangential spring.
#include "particles/integration/SemiImplicitEuler.hpp"
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/TangentialSpring.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

/// Free flight under gravity for n steps with `integrator` (no contacts).
template <Integrator I>
ParticleStorage freeFlight(I const& integrator, double dt, int n, Vec3 const& g) {
    ParticleStorage ps;
    ps.add(sphere(1, Vec3(1, 2, 3), 0.5, 2.0, Vec3(0.5, -1, 4)));
    ParticleInit fixed = sphere(2, Vec3(5, 5, 5), 0.5, 1.0, Vec3(1, 1, 1));
    fixed.flags = Flag::Fixed;
    ps.add(fixed);
    ParticleInit shadow = sphere(3, Vec3(7, 7, 7), 0.5, 1.0, Vec3(1, 1, 1));
    shadow.flags = Flag::Shadow;
    ps.add(shadow);
    for (int k = 0; k < n; ++k) {
        integrator.preForce(ps, dt, g);
        ps.resetForces();
        ps.force(1) = Vec3(100, 0, 0); // a force on the fixed one must not move it
        ps.force(2) = Vec3(100, 0, 0); // nor on the shadow (its master moves it)
        integrator.postForce(ps, dt, g);
    }
    return ps;
}

} // namespace

TEST(Integration, FreeFlightUnderGravity) {
    Vec3 const g(0, 0, -9.81), x0(1, 2, 3), v0(0.5, -1, 4);
    double const dt = 1e-3;
    int const n = 1000;
    double const t = dt * n;
    Vec3 const exact = x0 + v0 * t + 0.5 * g * t * t;
    // Velocity Verlet integrates a constant force exactly (round-off only).
    ParticleStorage const vv = freeFlight(VelocityVerlet{}, dt, n, g);
    EXPECT_LT((vv.position(0) - exact).norm(), 1e-11);
    EXPECT_LT((vv.velocity(0) - (v0 + g * t)).norm(), 1e-11);
    // Semi-implicit Euler: exact velocity, positions ahead by g t dt / 2 (first order).
    ParticleStorage const se = freeFlight(SemiImplicitEuler{}, dt, n, g);
    EXPECT_LT((se.position(0) - (exact + 0.5 * g * t * dt)).norm(), 1e-11);
    EXPECT_LT((se.velocity(0) - (v0 + g * t)).norm(), 1e-11);
    for (ParticleStorage const* ps : {&vv, &se}) {
        EXPECT_EQ(ps->position(1), Vec3(5, 5, 5)); // fixed
        EXPECT_EQ(ps->position(2), Vec3(7, 7, 7)); // shadow
        EXPECT_EQ(ps->velocity(2), Vec3(1, 1, 1));
    }
}

TEST(Integration, RotationIsTheExactQuaternionOfOmegaDt) {
    Vec3 const w(0.3, -1.2, 2.0);
    double const dt = 0.01;
    int const n = 5000;
    for (int scheme = 0; scheme < 2; ++scheme) {
        ParticleStorage ps;
        ps.add(sphere(1, Vec3::Zero(), 1.0, 1.0));
        ps.angularVelocity(0) = w;
        for (int k = 0; k < n; ++k) {
            if (scheme == 0) {
                VelocityVerlet{}.preForce(ps, dt, Vec3::Zero());
                VelocityVerlet{}.postForce(ps, dt, Vec3::Zero());
            } else {
                SemiImplicitEuler{}.postForce(ps, dt, Vec3::Zero());
            }
        }
        regolith::core::Quat const exact(Eigen::AngleAxisd(w.norm() * dt * n, w.normalized()));
        EXPECT_LT(ps.orientation(0).angularDistance(exact), 1e-10);
        EXPECT_NEAR(ps.orientation(0).norm(), 1.0, 1e-14);
    }
    // A torque changes omega by tau / I dt per step (isotropic sphere).
    ParticleStorage ps;
    ps.add(sphere(1, Vec3::Zero(), 0.5, 2.0));
    ps.torque(0) = Vec3(0, 0, 1);
    SemiImplicitEuler{}.postForce(ps, 0.1, Vec3::Zero());
    EXPECT_NEAR(ps.angularVelocity(0).z(), 0.1 / (0.4 * 2.0 * 0.25), 1e-14);
}

TEST(Integration, WithoutOrientationOnlyTheQuaternionStays) {
    // time.orientation = false: x, v and omega bit for bit as with the rotation, q untouched.
    Vec3 const g(0, 0, -9.81);
    auto run = [&](VelocityVerlet const& vv) {
        ParticleStorage ps;
        ps.add(sphere(1, Vec3(1, 2, 3), 0.5, 2.0, Vec3(0.5, -1, 4)));
        ps.angularVelocity(0) = Vec3(0.3, -1.2, 2.0);
        for (int k = 0; k < 100; ++k) {
            vv.preForce(ps, 0.01, g);
            ps.force(0) = Vec3(0.1 * k, -0.2, 0.3);
            ps.torque(0) = Vec3(0.01, 0.02 * k, -0.03);
            vv.postForce(ps, 0.01, g);
        }
        return ps;
    };
    ParticleStorage const with = run(VelocityVerlet{});
    ParticleStorage const without = run(VelocityVerlet{.orientation = false});
    EXPECT_EQ(with.position(0), without.position(0));
    EXPECT_EQ(with.velocity(0), without.velocity(0));
    EXPECT_EQ(with.angularVelocity(0), without.angularVelocity(0));
    EXPECT_GT(with.orientation(0).angularDistance(regolith::core::Quat::Identity()), 0.1);
    EXPECT_EQ(without.orientation(0).coeffs(), regolith::core::Quat::Identity().coeffs());
}

TEST(ContactEvaluation, ForcesOnBothPartnersIncludingShadows) {
    LinearContactParams p;
    p.stiffness = 1000.0;
    p.tangentialStiffness = 300.0;
    p.restitution = 0.8;
    p.friction = 0.4;
    SpringDashpot const model{MaterialTable<LinearContactParams>(1, p)};
    ParticleStorage ps;
    ps.add(sphere(9, Vec3(0.9, 0, 0), 0.5, 1.0, Vec3(-1, 0.5, 0)));
    ParticleInit shadow = sphere(4, Vec3(0, 0, 0), 0.5, 2.0);
    shadow.flags = Flag::Shadow;
    ps.add(shadow);
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    detector.detect(ps, walls, everywhere(), contacts);
    ASSERT_EQ(contacts.pairs.size(), 1U);
    Contact const& c = contacts.pairs[0];
    EXPECT_EQ(ps.uid(c.i), 4U); // the shadow has the smaller uid: it is i and holds history
    evaluateContacts(ps, walls, contacts, model, 1e-3, 1);
    EXPECT_GT(ps.force(1).norm(), 0.0);
    EXPECT_EQ(ps.force(0), Vec3(-ps.force(1)));
    EXPECT_GT(ps.force(0).x(), p.stiffness * 0.1); // spring plus damping of the approach
    ASSERT_NE(ps.history(1).find(9), nullptr);     // spring stored on i, keyed by uid(j)
    EXPECT_EQ(ps.history(0).size(), 0U);
    // The tangential force opposes j's sliding (+y) and is below the Coulomb limit.
    EXPECT_LT(ps.force(0).y(), 0.0);
    EXPECT_LE(std::abs(ps.force(0).y()), p.friction * ps.force(0).x() + 1e-12);
    // Torques: the tangential force at the contact point (the midpoint, equal radii) spins
    // both the same way with equal lever arms.
    EXPECT_GT(ps.torque(0).z(), 0.0);
    EXPECT_NEAR(ps.torque(0).z(), ps.torque(1).z(), 1e-12);
    // A later pass without that contact drops the history.
    pruneHistory(ps, 2);
    EXPECT_TRUE(ps.history(1).empty());
}

TEST(TangentialSpring, ProjectionAndCoulombLimit) {
    Vec3 const n = Vec3(1, 1, 0).normalized();
    Vec3 s(1, 0, 0.5);
    double const len = s.norm();
    projectSpring(s, n);
    EXPECT_NEAR(s.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(s.norm(), len, 1e-15);

    // Sticking: the spring grows by v_t dt per step, the force is -kt s - ct v_t.
    Vec3 spring = Vec3::Zero();
    Vec3 const vt(0, 0, 2.0);
    Vec3 f = Vec3::Zero();
    for (int k = 0; k < 10; ++k)
        f = tangentialForce(spring, Vec3::UnitX(), vt, 100.0, 1.0, 1e9, 1e-3);
    EXPECT_NEAR(spring.z(), 10 * 2.0 * 1e-3, 1e-15);
    EXPECT_NEAR(f.z(), -100.0 * 0.02 - 2.0, 1e-12);
    // Sliding: |F| = limit exactly, and the spring is what that force implies.
    for (int k = 0; k < 100; ++k)
        f = tangentialForce(spring, Vec3::UnitX(), vt, 100.0, 1.0, 3.0, 1e-3);
    EXPECT_NEAR(f.norm(), 3.0, 1e-12);
    EXPECT_NEAR((-100.0 * spring - 1.0 * vt - f).norm(), 0.0, 1e-12);
    // No friction: no force, no memory.
    f = tangentialForce(spring, Vec3::UnitX(), vt, 100.0, 1.0, 0.0, 1e-3);
    EXPECT_EQ(f, Vec3::Zero());
    EXPECT_EQ(spring, Vec3::Zero());
}
