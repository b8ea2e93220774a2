// Two-body normal impacts against the analytic restitution and contact time, and what
// happens when the time step is too large.
#include "particles/integration/SemiImplicitEuler.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::InputError;

namespace {

// Unequal spheres approaching head-on at relative speed 1: m_eff = 1 * 3 / 4 = 0.75.
constexpr double kMassA = 1.0, kMassB = 3.0, kRadiusA = 0.5, kRadiusB = 0.7;
constexpr double kEffMass = kMassA * kMassB / (kMassA + kMassB);

void addPair(ParticleStorage& ps, double gap, double vRel = 1.0) {
    double const xb = kRadiusA + kRadiusB + gap;
    // Momentum-free frame: the centre of mass stays at rest.
    double const va = vRel * kMassB / (kMassA + kMassB);
    double const vb = -vRel * kMassA / (kMassA + kMassB);
    ps.add(sphere(1, Vec3::Zero(), kRadiusA, kMassA, Vec3(va, 0, 0)));
    ps.add(sphere(2, Vec3(xb, 0, 0), kRadiusB, kMassB, Vec3(vb, 0, 0)));
}

SpringDashpot linearModel(double k, double e) {
    LinearContactParams p;
    p.stiffness = k;
    p.tangentialStiffness = 2.0 / 7.0 * k;
    p.restitution = e;
    p.friction = 0.5;
    return SpringDashpot(MaterialTable<LinearContactParams>(1, p));
}

template <class Integ>
Collision linearImpact(double e, double dtFraction, double gap = 0.01) {
    double const k = 1e4;
    SpringDashpot const model = linearModel(k, e);
    LinearContactParams const& p = model.materials()(0, 0);
    double const tc = SpringDashpot::contactTime(p, kEffMass);
    ParticleStorage ps;
    WallList walls;
    addPair(ps, gap);
    BlockStepper stepper(ps, walls, model, Integ{}, tc * dtFraction);
    return runCollision(ps, stepper, 1000000);
}

} // namespace

TEST(LinearImpact, RestitutionAndContactTimeMatchTheory) {
    // Tolerance 1 % (the bound); at dt = t_c / 1000 the discretisation error is at
    // most 0.2 % on e (at e = 0.1, where the damping is strongest) and 0.05 % on t_c.
    double const k = 1e4;
    for (double e : {0.1, 0.5, 0.9, 1.0}) {
        double const tc = SpringDashpot::contactTime(linearModel(k, e).materials()(0, 0), kEffMass);
        // The closed form: t_c = pi / sqrt(k/m - gamma^2), gamma from e.
        double const w0 = std::sqrt(k / kEffMass);
        double const gamma =
            -std::log(e) * w0 /
            std::sqrt(std::numbers::pi * std::numbers::pi + std::log(e) * std::log(e));
        EXPECT_NEAR(tc, std::numbers::pi / std::sqrt(w0 * w0 - gamma * gamma), 1e-12 * tc);
        EXPECT_NEAR(std::exp(-gamma * tc), e, 1e-12);

        Collision const c = linearImpact<VelocityVerlet>(e, 1e-3);
        SCOPED_TRACE(::testing::Message() << "e = " << e);
        ASSERT_TRUE(c.separated);
        EXPECT_NEAR(c.restitution, e, 0.01 * e);
        EXPECT_NEAR(c.contactTime, tc, 0.01 * tc);
        // The contact had a history entry on the smaller uid, dropped once broken.
        EXPECT_EQ(c.maxHistory, 1U);
        EXPECT_EQ(c.historyAfter, 0U);
        // Semi-implicit Euler and kick-drift-kick Verlet are the same leapfrog map when the
        // first force is zero (Euler's v_n is Verlet's v_{n-1/2}; both evaluate the damping
        // with the latest velocity), so after the collision their velocities agree to
        // round-off (two half kicks against one full kick).
        Collision const euler = linearImpact<SemiImplicitEuler>(e, 1e-3);
        EXPECT_NEAR(euler.restitution, c.restitution, 1e-9);
    }
}

TEST(LinearImpact, MomentumIsConserved) {
    SpringDashpot const model = linearModel(1e4, 0.5);
    ParticleStorage ps;
    WallList walls;
    addPair(ps, 0.01);
    // An oblique, spinning encounter exercises the tangential spring and the torques too.
    ps.velocity(0) += Vec3(0, 0.3, 0.1);
    ps.position(1).y() = 0.4;
    ps.angularVelocity(1) = Vec3(0, 0, 5);
    auto momentum = [&ps] {
        return Vec3(ps.mass(0) * ps.velocity(0) + ps.mass(1) * ps.velocity(1));
    };
    auto angular = [&ps] {
        Vec3 l = Vec3::Zero();
        for (std::size_t i = 0; i < 2; ++i)
            l += ps.mass(i) * ps.position(i).cross(ps.velocity(i)) +
                 ps.angularVelocity(i) / ps.invInertia(i);
        return l;
    };
    Vec3 const p0 = momentum(), l0 = angular();
    BlockStepper stepper(ps, walls, model, VelocityVerlet{}, 1e-5);
    bool touched = false;
    for (int n = 0; n < 20000; ++n) {
        stepper.step();
        touched = touched || !stepper.contacts().pairs.empty();
    }
    EXPECT_TRUE(touched);
    // Contact forces are equal and opposite and torques include their moments: both are
    // conserved to round-off (relative 1e-12 of the initial magnitudes).
    EXPECT_LT((momentum() - p0).norm(), 1e-12 * p0.norm());
    EXPECT_LT((angular() - l0).norm(), 1e-10 * l0.norm());
    EXPECT_GT(ps.angularVelocity(0).norm(), 1e-3); // friction did transfer spin
}

TEST(HertzImpact, ContactTimeMatchesHertzTheory) {
    // Elastic (e = 1) Hertz impact; tolerance 2 % (the bound; the constant 2.87 is
    // the closed form to three digits, 2.868; the numerical error at dt = t_c / 2000 is far
    // smaller).
    double const youngs = 1e6, nu = 0.3;
    auto const p = HertzMindlinParams::fromMaterials(youngs, nu, youngs, nu, 1.0, 0.3);
    EXPECT_NEAR(p.effectiveYoungsModulus, youngs / (2.0 * (1.0 - nu * nu)), 1e-9 * youngs);
    HertzMindlin const model{MaterialTable<HertzMindlinParams>(1, p)};
    double const rEff = kRadiusA * kRadiusB / (kRadiusA + kRadiusB);
    for (double v : {0.5, 1.0, 2.0}) {
        double const closedForm =
            2.87 * std::pow(kEffMass * kEffMass /
                                (rEff * p.effectiveYoungsModulus * p.effectiveYoungsModulus * v),
                            0.2);
        double const tc = HertzMindlin::contactTime(p, kEffMass, rEff, v);
        ParticleStorage ps;
        WallList walls;
        addPair(ps, 0.001, v);
        BlockStepper stepper(ps, walls, model, VelocityVerlet{}, tc / 2000);
        Collision const c = runCollision(ps, stepper, 1000000);
        SCOPED_TRACE(::testing::Message() << "v = " << v);
        ASSERT_TRUE(c.separated);
        EXPECT_NEAR(c.contactTime, closedForm, 0.02 * closedForm);
        EXPECT_NEAR(c.restitution, 1.0, 1e-3); // elastic, symplectic integrator
    }
}

TEST(HertzImpact, DampedRestitutionDoesNotDependOnImpactVelocity) {
    // The Tsuji damping ~ delta^(1/4) scales like the Hertz force, so e(v) is constant
    // (Antypov & Elliott 2011); a damping without the delta^(1/4) factor fails this by far
    // more than the 0.5 % tolerance (which covers the O(dt) error at dt = t_c / 2000).
    auto const p = HertzMindlinParams::fromMaterials(1e6, 0.3, 1e6, 0.3, 0.5, 0.0);
    HertzMindlin const model{MaterialTable<HertzMindlinParams>(1, p)};
    double const rEff = kRadiusA * kRadiusB / (kRadiusA + kRadiusB);
    std::vector<double> measured;
    for (double v : {0.1, 1.0, 10.0}) {
        ParticleStorage ps;
        WallList walls;
        addPair(ps, 0.001, v);
        BlockStepper stepper(ps, walls, model, VelocityVerlet{},
                             HertzMindlin::contactTime(p, kEffMass, rEff, v) / 2000);
        Collision const c = runCollision(ps, stepper, 1000000);
        ASSERT_TRUE(c.separated);
        measured.push_back(c.restitution);
    }
    EXPECT_NEAR(measured[1], measured[0], 0.005 * measured[0]);
    EXPECT_NEAR(measured[2], measured[0], 0.005 * measured[0]);
    // And the Tsuji/LIGGGHTS mapping of e to beta gives the requested e = 0.5 within 1 %.
    EXPECT_NEAR(measured[0], 0.5, 0.005);
}

TEST(TimeStepFailure, RestitutionErrorGrowsWithDtAndTheGuardRefuses) {
    // The same collision (e = 0.9) at dt = t_c/5, t_c/2 and t_c. The error depends on where in
    // a step the contact begins, so each dt is averaged over eight start phases (gaps).
    double const e = 0.9;
    std::vector<double> errors;
    for (double fraction : {0.2, 0.5, 1.0}) {
        double sum = 0.0;
        for (int phase = 0; phase < 8; ++phase) {
            double const tc =
                SpringDashpot::contactTime(linearModel(1e4, e).materials()(0, 0), kEffMass);
            double const gap = 0.005 + (phase + 0.5) / 8.0 * tc * fraction; // |v_rel| = 1
            Collision const c = linearImpact<SemiImplicitEuler>(e, fraction, gap);
            EXPECT_TRUE(c.separated);
            sum += std::abs(c.restitution - e);
        }
        errors.push_back(sum / 8.0);
    }
    EXPECT_LT(errors[0], errors[1]);
    EXPECT_LT(errors[1], errors[2]);
    EXPECT_GT(errors[0], 0.005); // even t_c/5 is visibly wrong (1.4 %): hence the t_c/10 limit

    // The guard: t_c from the smallest mass (m_eff = m_min / 2 = 0.5, shorter than this pair's
    // 0.75) refuses all three by default and accepts them when told to.
    SpringDashpot const model = linearModel(1e4, e);
    ParticleStorage ps;
    addPair(ps, 0.01);
    ContactTimeEstimate const est = estimateContactTime(ps, model);
    EXPECT_NEAR(est.contactTime, SpringDashpot::undampedContactTime(model.materials()(0, 0), 0.5),
                1e-15);
    EXPECT_EQ(est.uid, 1U);
    EXPECT_EQ(est.mass, kMassA);
    double const tcPair = SpringDashpot::contactTime(model.materials()(0, 0), kEffMass);
    for (double fraction : {0.2, 0.5, 1.0}) {
        EXPECT_THROW(checkTimeStep(tcPair * fraction, est, false), InputError);
        EXPECT_NO_THROW(checkTimeStep(tcPair * fraction, est, true));
    }
    EXPECT_NO_THROW(checkTimeStep(est.contactTime / 10.0, est, false));
    EXPECT_THROW(checkTimeStep(est.contactTime / 10.0 * (1 + 1e-9), est, false), InputError);
}

TEST(TimeStepFailure, TheGuardsLimitIsStableAtAnyRestitution) {
    // The guard's t_c is the undamped duration: at t_c / 10, omega_0 dt = pi / 10, inside the
    // explicit step's stability bound 2 (sqrt(1 + zeta^2) - zeta) >= 0.83 for every damping
    // ratio zeta <= 1. The damped duration is 4.5x longer at e = 1e-6: with it a pair
    // blew up at a dt the guard accepted, and rebounded faster than it came at 0.7 x it.
    for (double e : {1e-6, 1e-3, 0.1}) {
        SCOPED_TRACE(::testing::Message() << "e = " << e);
        SpringDashpot const model = linearModel(1e4, e);
        ParticleStorage ps;
        WallList walls;
        addPair(ps, 0.01); // relative speed 1
        ContactTimeEstimate const est = estimateContactTime(ps, model);
        double const dt = est.contactTime / 10.0;
        EXPECT_NO_THROW(checkTimeStep(dt, est, false));
        BlockStepper stepper(ps, walls, model, VelocityVerlet{}, dt);
        double fastest = 0.0;
        for (int n = 0; n < 400; ++n) { // the contact lasts ~10 steps at most at e = 0.1
            stepper.step();
            fastest = std::max(fastest, (ps.velocity(1) - ps.velocity(0)).norm());
        }
        EXPECT_LE(fastest, 1.0 + 1e-12); // no energy from the integrator
        EXPECT_GE(ps.position(1).x() - ps.position(0).x(), 0.5 * (kRadiusA + kRadiusB));
    }
}

TEST(HertzImpact, SlidingFrictionOpposesTheSlipThroughTheContact) {
    // A sphere hits a wall obliquely, its tangential speed far above full sliding (4 against
    // 3.5 mu (1 + e) v_n = 1.26), low restitution: the friction must slow the slip at every
    // step and take at least mu (1 + e) v_n of it (the impulse mu J_n; a little more where F_n
    // turns attractive: max(F_n, 0) then caps nothing). A sliding spring that kept the
    // dashpot's share (c_t v_t / k_t, with k_t ~ a but c_t ~ sqrt(a)) turned into a force
    // along the slip while the contact loaded (0.63 of the impulse, the sphere sliding
    // faster than it came).
    double const e = 0.2, mu = 0.3, r = 0.5, m = 1.0;
    auto const p = HertzMindlinParams::fromMaterials(1e5, 0.3, 1e5, 0.3, e, mu);
    HertzMindlin const model{MaterialTable<HertzMindlinParams>(1, p)};
    ParticleStorage ps;
    WallList walls;
    walls.add(Vec3::Zero(), Vec3::UnitZ());
    ps.add(sphere(1, Vec3(0, 0, r + 0.001), r, m, Vec3(4.0, 0, -1.0)));
    BlockStepper stepper(ps, walls, model, VelocityVerlet{},
                         HertzMindlin::contactTime(p, m, r, 1.0) / 2000);
    double last = ps.velocity(0).x();
    bool slowing = true;
    for (int n = 0; n < 20000; ++n) {
        stepper.step();
        slowing = slowing && ps.velocity(0).x() <= last + 1e-12;
        last = ps.velocity(0).x();
    }
    double const taken = 4.0 - ps.velocity(0).x();
    EXPECT_TRUE(slowing);
    EXPECT_GT(taken, mu * (1.0 + e) * 0.99);
    EXPECT_LT(taken, mu * (1.0 + e) * 1.25);
    EXPECT_GT(ps.velocity(0).z(), 0.0); // it bounced
}

TEST(HertzImpact, ModelCRollingCoupleOnlySlowsTheSpin) {
    // A spinning sphere dropped on a wall without friction: the only torque is model C's
    // rolling couple, which must slow the spin (by at most mu_r r J_n / I, a little more where
    // F_n turns attractive) and never add energy. Its slider kept the dashpot's share, which
    // grew into a couple along the rolling as the Hertz contact loaded (k_r ~ a): the spin
    // rose from 20 to 20.24.
    double const e = 0.2, muRoll = 0.1, r = 0.5, m = 1.0, spin = 20.0;
    auto p = HertzMindlinParams::fromMaterials(1e5, 0.3, 1e5, 0.3, e, 0.0, muRoll);
    p.rollingSpring.enabled = true; // default damping ratio 0.3
    HertzMindlin const model{MaterialTable<HertzMindlinParams>(1, p)};
    ParticleStorage ps;
    WallList walls;
    walls.add(Vec3::Zero(), Vec3::UnitZ());
    ParticleInit grain = sphere(1, Vec3(0, 0, r + 0.001), r, m, Vec3(0, 0, -1.0));
    grain.angularVelocity = Vec3(0, spin, 0);
    ps.add(grain);
    BlockStepper stepper(ps, walls, model, VelocityVerlet{},
                         HertzMindlin::contactTime(p, m, r, 1.0) / 2000);
    for (int n = 0; n < 20000; ++n)
        stepper.step();
    double const inertia = 0.4 * m * r * r;
    double const jn = m * (1.0 + e) * 1.0;
    double const slowed = spin - ps.angularVelocity(0).y();
    EXPECT_GT(slowed, 0.99 * muRoll * r * jn / inertia);
    EXPECT_LT(slowed, 1.25 * muRoll * r * jn / inertia);
    EXPECT_GT(ps.velocity(0).z(), 0.0); // it bounced
}
