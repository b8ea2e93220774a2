// The momentum-conserving dual tree: total force zero to round-off, accuracy against the
// direct sum falling with θ, the centre of mass of an isolated two-pile system still after
// 1,000 leapfrog steps (next to the plain tree, which drifts), and the gathered parallel
// variant equal to the serial one. The kernel is serial: the single-rank tests skip at np > 1.
#include "gravity/tree/MutualTree.hpp"

#include "gravity/tree/BarnesHut.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <functional>

using namespace regolith;
using namespace regolith::testing;
namespace gt = regolith::gravity::tree;

namespace {

gt::TreeOptions withTheta(double theta) {
    gt::TreeOptions o;
    o.theta = theta;
    return o;
}

/// Two agglomerates of n grains each, 1,500 m apart, approaching at 0.05 m/s transversally.
struct TwoPiles {
    gravity::samples::Body body;
    std::vector<double> vx, vy, vz;
};

TwoPiles twoPiles(std::size_t n) {
    TwoPiles p;
    auto const a = gravity::samples::packedAgglomerate(n, 20.0, 60.0, 3000.0, 0.3,
                                                       core::Vec3(-750.0, 0.0, 0.0), 1);
    auto const b = gravity::samples::packedAgglomerate(n, 20.0, 60.0, 3000.0, 0.3,
                                                       core::Vec3(750.0, 0.0, 0.0), 2);
    for (std::size_t i = 0; i < n; ++i) {
        p.body.push(a, i);
        p.vx.push_back(0.0);
        p.vy.push_back(0.05);
        p.vz.push_back(0.0);
    }
    for (std::size_t i = 0; i < n; ++i) {
        p.body.push(b, i);
        p.vx.push_back(0.0);
        p.vy.push_back(-0.05);
        p.vz.push_back(0.0);
    }
    // Zero total momentum: the centre of mass should stand still.
    double py = 0.0;
    double mass = 0.0;
    for (std::size_t i = 0; i < p.body.size(); ++i) {
        py += p.body.m[i] * p.vy[i];
        mass += p.body.m[i];
    }
    for (double& v : p.vy)
        v -= py / mass;
    return p;
}

core::Vec3 centreOfMass(gravity::samples::Body const& b) {
    core::Vec3 c = core::Vec3::Zero();
    double mass = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        c += b.m[i] * core::Vec3(b.x[i], b.y[i], b.z[i]);
        mass += b.m[i];
    }
    return c / mass;
}

/// Kick-drift-kick leapfrog for `steps` steps of `dt` s with the field `eval`; returns the
/// largest distance (m) of the centre of mass from its start (the total momentum is zero).
double comDrift(TwoPiles p, int steps, double dt,
                std::function<void(gravity::samples::Body const&, Field&)> const& eval) {
    core::Vec3 const start = centreOfMass(p.body);
    Field f(p.body.size());
    eval(p.body, f);
    double drift = 0.0;
    for (int s = 0; s < steps; ++s) {
        for (std::size_t i = 0; i < p.body.size(); ++i) {
            p.vx[i] += 0.5 * dt * f.ax[i];
            p.vy[i] += 0.5 * dt * f.ay[i];
            p.vz[i] += 0.5 * dt * f.az[i];
            p.body.x[i] += dt * p.vx[i];
            p.body.y[i] += dt * p.vy[i];
            p.body.z[i] += dt * p.vz[i];
        }
        eval(p.body, f);
        for (std::size_t i = 0; i < p.body.size(); ++i) {
            p.vx[i] += 0.5 * dt * f.ax[i];
            p.vy[i] += 0.5 * dt * f.ay[i];
            p.vz[i] += 0.5 * dt * f.az[i];
        }
        drift = std::max(drift, (centreOfMass(p.body) - start).norm());
    }
    return drift;
}

} // namespace

TEST(MutualTree, TotalForceVanishesAndErrorFallsWithTheta) {
    if (world().size() > 1)
        GTEST_SKIP() << "serial kernel";
    auto const body = testAgglomerate(5000, 9);
    Field const ref = referenceField(body, body, gravity::kNewtonG);
    double previous = 1.0;
    for (double const theta : {0.7, 0.5, 0.3}) {
        gt::MutualTree tree(withTheta(theta));
        Field f(body.size());
        tree.evaluate(body.view(), f.out());
        auto const e = gravity::errorStats(world(), gravity::relativeErrors(f.view(), ref.view()));
        double const total = relativeTotalForce(world(), body.m, f);
        std::printf("mutual tree theta %.1f: median %.3e p99 %.3e, |sum m a| / sum m|a| = "
                    "%.2e\n",
                    theta, e.median, e.p99, total);
        EXPECT_LE(total, 1e-14);
        EXPECT_LT(e.median, previous);
        previous = e.median;
        if (theta == 0.5) {
            EXPECT_LE(e.median, 1e-2);
        }
    }
    // The plain tree, for contrast, leaves a net force far above round-off.
    gt::BarnesHut plain(world(), withTheta(0.5));
    Field f(body.size());
    plain.evaluate(body.view(), f.out());
    double const plainTotal = relativeTotalForce(world(), body.m, f);
    std::printf("plain tree theta 0.5: |sum m a| / sum m|a| = %.2e\n", plainTotal);
    EXPECT_GT(plainTotal, 1e-10);
}

TEST(MutualTree, CentreOfMassOfTwoPilesStaysPut) {
    if (world().size() > 1)
        GTEST_SKIP() << "serial kernel";
    TwoPiles const piles = twoPiles(300);
    double const dt = 20.0; // s; the free-fall time of a pile is ~ 1 / sqrt(G ρ) ~ 2e3 s
    gt::TreeOptions o = withTheta(0.5);
    o.softening = 20.0;
    gt::MutualTree mutual(o);
    double const mutualDrift = comDrift(
        piles, 1000, dt, [&](auto const& b, Field& f) { mutual.evaluate(b.view(), f.out()); });
    gt::BarnesHut plain(world(), o);
    double const plainDrift = comDrift(
        piles, 1000, dt, [&](auto const& b, Field& f) { plain.evaluate(b.view(), f.out()); });
    std::printf("centre-of-mass drift over 1000 steps: mutual %.3e m, plain tree %.3e m "
                "(smallest grain radius 20 m)\n",
                mutualDrift, plainDrift);
    EXPECT_LE(mutualDrift, 1e-9 * 750.0); // round-off of positions ~1e3 m
    EXPECT_GT(plainDrift, 100.0 * mutualDrift);
}

TEST(MutualTree, GatheredEqualsSerial) {
    auto const body = testAgglomerate(1200, 4);
    auto const local = localSlab(world(), body);
    gt::MutualTree tree(withTheta(0.5));
    Field par(local.size());
    tree.evaluateGathered(world(), local.view(), par.out());
    // The serial evaluation of the slabs concatenated in rank order.
    gravity::samples::Body ordered;
    for (int r = 0; r < world().size(); ++r) {
        auto const slab = gravity::samples::slabOf(body, r, world().size());
        for (std::size_t i = 0; i < slab.size(); ++i)
            ordered.push(slab, i);
    }
    Field ser(ordered.size());
    tree.evaluate(ordered.view(), ser.out());
    std::size_t offset = 0;
    for (int r = 0; r < world().rank(); ++r)
        offset += gravity::samples::slabOf(body, r, world().size()).size();
    for (std::size_t i = 0; i < local.size(); ++i) {
        EXPECT_EQ(par.ax[i], ser.ax[offset + i]);
        EXPECT_EQ(par.az[i], ser.az[offset + i]);
    }
}
