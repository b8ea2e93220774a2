// The rubble-pile app's pieces against closed forms: the pile's spin and equivalent ellipsoid,
// the friends-of-friends remnant, the hyperbolic pass, the tidal field and the spin-up
// torque, and the spin-up rate's refusal.
#include "apps/spin_up/PileMeasures.hpp"
#include "apps/spin_up/PileRecordFile.hpp"
#include "apps/spin_up/Remnants.hpp"
#include "apps/spin_up/RubblePileSections.hpp"
#include "apps/spin_up/SpinUpTorque.hpp"
#include "apps/spin_up/TidalFlyby.hpp"
#include "core/Error.hpp"
#include "domain/BlockForest.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace regolith;
using apps::MasterRecord;
using core::Vec3;

namespace {

MasterRecord grain(std::uint64_t uid, Vec3 const& x, double radius = 0.0, double mass = 1.0) {
    MasterRecord g;
    g.uid = uid;
    g.position = x;
    g.radius = radius;
    g.mass = mass;
    return g;
}

/// Grains of mass 2 at `positions` as masters of a one-block forest, on this rank alone.
struct OneBlock {
    core::Comm comm{MPI_COMM_SELF};
    domain::BlockForest forest;
    particles::LocalParticles local;
    explicit OneBlock(std::vector<Vec3> const& positions)
        : forest(comm,
                 [] {
                     domain::ForestSpec s;
                     s.domain = core::AABB{Vec3::Constant(-10.0), Vec3::Constant(10.0)};
                     return s;
                 }())
        , local(forest) {
        for (std::size_t k = 0; k < positions.size(); ++k) {
            particles::ParticleInit p;
            p.uid = k;
            p.position = positions[k];
            p.radius = 0.1;
            p.mass = 2.0;
            (void)local.addMaster(p);
        }
    }
    Vec3 force(std::size_t k) const {
        particles::ParticleStorage const& g = local.blocks()[0].particles;
        return g.force(g.find(k));
    }
};

} // namespace

TEST(PileMeasures, SixPointsTurningRigidlyGiveTheirSpinAndEllipsoid) {
    // Point masses at +-a x, +-b y, +-c z: I_x = 2 m (b^2 + c^2) and so on, so the uniform
    // ellipsoid of the same moments has semi-axes sqrt(5/3) (a, b, c).
    double const a = 3.0, b = 2.0, c = 1.0, omega = 0.7;
    Vec3 const centre(10.0, -4.0, 2.0);
    std::vector<MasterRecord> g;
    for (Vec3 const& d : {Vec3(a, 0, 0), Vec3(0, b, 0), Vec3(0, 0, c)})
        for (double s : {1.0, -1.0}) {
            g.push_back(grain(g.size(), centre + s * d));
            g.back().velocity = omega * Vec3::UnitZ().cross(s * d);
        }
    g.push_back(grain(g.size(), centre + Vec3(50.0, 0, 0))); // beyond the radius: outside
    apps::PileMeasures const p =
        apps::measurePile(g, centre + Vec3(0.5, 0, 0), 10.0, Vec3(0, 0, 2.0));
    EXPECT_DOUBLE_EQ(p.mass, 6.0);
    EXPECT_DOUBLE_EQ(p.outsideMass, 1.0);
    EXPECT_NEAR((p.centre - centre).norm(), 0.0, 1e-12);
    EXPECT_NEAR(p.spin, omega, 1e-12);
    double const k = std::sqrt(5.0 / 3.0);
    EXPECT_NEAR(p.axes[0], k * a, 1e-12);
    EXPECT_NEAR(p.axes[1], k * b, 1e-12);
    EXPECT_NEAR(p.axes[2], k * c, 1e-12);
    // A sphere of bulk density rho: omega_c^2 = 4 pi G rho / 3 = G M / (a b c).
    EXPECT_NEAR(p.criticalSpin(2.0), std::sqrt(2.0 * 6.0 / (k * a * k * b * k * c)), 1e-12);
}

TEST(Remnants, FriendsOfFriendsLinkChainsWithinTheGapOnly) {
    // A chain of 4 grains (gaps 0.05) and a pair (gap 0.05) 0.3 apart from it, and a single
    // grain: with a gap of 0.1, three clusters; the chain (uids 0-3) is the largest.
    std::vector<MasterRecord> g;
    for (int i = 0; i < 4; ++i)
        g.push_back(grain(g.size(), Vec3(1.05 * i, 0, 0), 0.5));
    for (int i = 0; i < 2; ++i)
        g.push_back(grain(g.size(), Vec3(1.05 * 3 + 1.3 + 1.05 * i, 0, 0), 0.5, 1.5));
    g.push_back(grain(g.size(), Vec3(0, 5.0, 0), 0.5));
    apps::Remnant const r = apps::largestRemnant(g, 0.1);
    EXPECT_EQ(r.clusters, 3u);
    EXPECT_EQ(r.grains, 4u);
    EXPECT_DOUBLE_EQ(r.mass, 4.0);
    EXPECT_NEAR(r.centre.x(), 1.5 * 1.05, 1e-12);
    // A wider gap joins the pair to the chain.
    EXPECT_EQ(apps::largestRemnant(g, 0.31).grains, 6u);
}

TEST(HyperbolicPass, ReachesPeriapsisHalfwayAndFollowsVisViva) {
    double const mu = 3.0, q = 2.0, e = 1.8, start = 20.0;
    apps::HyperbolicPass const pass(mu, q, e, start);
    EXPECT_NEAR(pass.position(0.0).norm(), start, 1e-9);
    EXPECT_NEAR(pass.position(pass.duration()).norm(), start, 1e-9);
    Vec3 const peri = pass.position(0.5 * pass.duration());
    EXPECT_NEAR(peri.x(), q, 1e-9);
    EXPECT_NEAR(peri.y(), 0.0, 1e-9);
    EXPECT_LT(pass.position(0.0).y(), 0.0); // approaching from -y
    // Vis-viva, v^2 = mu (2 / r + 1 / a) with a = q / (e - 1), by central differences.
    double const a = q / (e - 1.0), h = 1e-5;
    for (double t : {0.1, 0.4, 0.5, 0.77}) {
        double const time = t * pass.duration();
        Vec3 const v = (pass.position(time + h) - pass.position(time - h)) / (2.0 * h);
        double const r = pass.position(time).norm();
        EXPECT_NEAR(v.squaredNorm(), mu * (2.0 / r + 1.0 / a), 1e-6 * mu / q) << t;
    }
    EXPECT_NEAR(pass.speedAtInfinity(), std::sqrt(mu / a), 1e-12);
}

TEST(TidalFlyby, RocheRadiusOfAFluidBody) {
    // 2.44 R_M (rho_M / rho)^(1/3) for a primary of radius R_M: here R_M = 1, rho_M = 3 rho.
    double const rho = 1.0, M = 4.0 / 3.0 * std::numbers::pi * 3.0 * rho;
    EXPECT_NEAR(apps::rocheRadius(M, rho), 2.44 * std::cbrt(3.0), 1e-12);
}

TEST(SpinUpSection, ARateTheRunCannotFollowIsRefusedNamingTheKey) {
    auto const fast = core::ConfigTable::fromString("[spin_up]\nrate = 0.5\n", "s.toml");
    try {
        (void)apps::parseRubblePileScene(fast);
        FAIL() << "a rate of 0.5 omega_c^2 was accepted";
    } catch (core::InputError const& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.toml:2: spin_up.rate: expected a spin-up rate in (0, 0.1] omega_c per "
                  "dynamical time 1 / omega_c (faster, the pile is kicked rather than spun up), "
                  "got 0.5");
    }
    auto const root = core::ConfigTable::fromString(
        "[spin_up]\nrate = 0.02\nfinal_spin = 1.2\n[flyby]\nmass = 1.0\n", "s.toml");
    apps::RubblePileScene const scene = apps::parseRubblePileScene(root);
    ASSERT_TRUE(scene.spinUp && scene.flyby);
    EXPECT_NO_THROW(apps::checkSpinUpRate(*scene.spinUp, 1.45, 1e-3));
    try {
        apps::checkSpinUpRate(*scene.spinUp, 1.45, 0.1);
        FAIL() << "a turn of 0.17 rad per step was accepted";
    } catch (core::InputError const& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.toml:3: spin_up.final_spin: at 1.2 omega_c (omega_c = 1.45) the pile turns "
                  "0.174 rad per step of time.dt = 0.1, too coarse for its grains' orbits; "
                  "expected at most 0.02 rad per step: lower time.dt or the spin");
    }
    apps::SpinUpSection inCode; // made in code: the key without a location
    inCode.rate = 0.5;
    try {
        apps::checkSpinUpRate(inCode, 1.45, 1e-3);
        FAIL() << "a rate of 0.5 omega_c^2 was accepted";
    } catch (core::InputError const& e) {
        EXPECT_EQ(std::string(e.what()),
                  "spin_up.rate: 0.5 omega_c per dynamical time 1 / omega_c = 0.6897 is too fast "
                  "for the pile to follow; expected at most 0.1");
    }
}

TEST(SpinUpSection, ASceneWithNothingDoneToThePileIsRefused) {
    auto const root = core::ConfigTable::fromString("[pile]\nradius = 2.0\n", "s.toml");
    EXPECT_THROW((void)apps::parseRubblePileScene(root), core::InputError);
    auto const bad =
        core::ConfigTable::fromString("[flyby]\nmass = 1.0\neccentricity = 0.5\n", "s.toml");
    EXPECT_THROW((void)apps::parseRubblePileScene(bad), core::InputError);
}

TEST(TidalFlyby, TheFieldVanishesAtTheCentreAndStretchesAlongTheLineToThePerturber) {
    // A perturber at distance D along x: to first order in d / D the tidal acceleration is
    // G M (2 d_x, -d_y, -d_z) / D^3 (the quadrupole term).
    Vec3 const c(1.0, -2.0, 0.5);
    double const D = 1000.0, gm = 3.0e6, d = 0.5;
    OneBlock pile({c, c + Vec3(d, 0, 0), c + Vec3(0, d, 0), c + Vec3(0, 0, -d)});
    apps::addTidalForce(pile.local, c, c + Vec3(D, 0, 0), gm);
    double const k = 2.0 * gm / (D * D * D); // mass 2 times G M / D^3
    EXPECT_NEAR(pile.force(0).norm(), 0.0, 1e-12 * k);
    EXPECT_NEAR(pile.force(1).x(), 2.0 * k * d, 2e-3 * k * d);
    EXPECT_NEAR(pile.force(2).y(), -k * d, 2e-3 * k * d);
    EXPECT_NEAR(pile.force(3).z(), k * d, 2e-3 * k * d);
}

TEST(SpinUpTorque, TurnsAboutTheAxisThroughTheCentreWithinTheReachOnly) {
    Vec3 const c(1.0, 1.0, 1.0);
    OneBlock pile({c + Vec3(2, 0, 0), c + Vec3(0, 0, 3), c + Vec3(0, -1, 0), c + Vec3(5, 0, 0)});
    apps::addSpinUpTorque(pile.local, c, Vec3::UnitZ(), 0.5, 4.0);
    EXPECT_NEAR((pile.force(0) - Vec3(0, 2.0 * 0.5 * 2, 0)).norm(), 0.0, 1e-15); // m alpha z x r
    EXPECT_NEAR(pile.force(1).norm(), 0.0, 1e-15);                               // on the axis
    EXPECT_NEAR((pile.force(2) - Vec3(2.0 * 0.5, 0, 0)).norm(), 0.0, 1e-15);
    EXPECT_EQ(pile.force(3), Vec3::Zero()); // beyond the reach: shed, left alone
}

TEST(PileRecordFile, ARestartKeepsTheRowsUpToItsCheckpointAndTheReference) {
    std::string const head = "# mass=2.5 bulk_radius=3 omega_c=1.25 spin=0.5 centre_x=1 centre_y=2 "
                             "centre_z=3 mean_grain_radius=0.5\n"
                             "time,spin_over_omega_c,shed_fraction,centre_x,centre_y,centre_z\n";
    std::string const rows = "0,0.4,0,1,2,3\n0.5,0.6,0.01,1.5,2,3\n1,0.5,0.02,2,2,3\n";
    apps::ResumedRecord const r = apps::resumeRecord(head + rows, 0.5, "p.csv");
    EXPECT_EQ(r.reference.mass, 2.5);
    EXPECT_EQ(r.reference.omegaC, 1.25);
    EXPECT_EQ(r.reference.centre, Vec3(1, 2, 3));
    EXPECT_EQ(r.reference.meanGrainRadius, 0.5);
    EXPECT_EQ(r.centre, Vec3(1.5, 2, 3)); // the last kept row's
    EXPECT_EQ(r.spins, (std::vector<double>{0.4, 0.6}));
    EXPECT_EQ(r.onset, 0.6);
    EXPECT_EQ(r.kept, head + "0,0.4,0,1,2,3\n0.5,0.6,0.01,1.5,2,3\n");
    EXPECT_THROW((void)apps::resumeRecord("", 1.0, "p.csv"), core::InputError);
    EXPECT_THROW((void)apps::resumeRecord("# mass=2\ntime\n", 1.0, "p.csv"), core::InputError);
}
