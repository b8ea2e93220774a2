// The self-gravity method registry: a method of one's own, registered from this file (a plain
// O(N^2) sum over the grains gathered on every rank, with a scene key of its own), runs through
// coupling::Simulation as "direct" does and gives the same grains to round-off; an unknown
// name lists the registered methods; taken names are refused.
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "gravity/common/GatherAll.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <any>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

using namespace regolith;
using core::Vec3;

namespace {

/// The method's own setting: gravity.pairwise_batch, the sources summed per pass (any count
/// gives the same bits: each target sums its sources in the same order).
struct PairwiseOptions {
    std::int64_t batch = 64;
};

/// Every grain on every rank, each target summing all sources in one order fixed by their
/// positions (so the bits do not depend on the ranks or blocks).
class PairwiseSum final : public coupling::GravityMethod {
public:
    explicit PairwiseSum(coupling::GravityMethodInput const& in)
        : m_comm(in.comm)
        , m_G(in.config.G)
        , m_options(in.config.options.has_value()
                        ? std::any_cast<PairwiseOptions>(in.config.options)
                        : PairwiseOptions{}) {}

    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        gravity::OwnedMasses const all = gravity::gatherAll(m_comm, grains);
        std::vector<std::size_t> order(all.x.size());
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return std::tie(all.x[a], all.y[a], all.z[a]) < std::tie(all.x[b], all.y[b], all.z[b]);
        });
        auto const batch = static_cast<std::size_t>(m_options.batch);
        double energy = 0.0;
        for (std::size_t i = 0; i < grains.size(); ++i) {
            double ax = 0.0, ay = 0.0, az = 0.0, phi = 0.0;
            for (std::size_t first = 0; first < order.size(); first += batch)
                for (std::size_t k = first; k < std::min(first + batch, order.size()); ++k) {
                    std::size_t const j = order[k];
                    double const dx = all.x[j] - grains.x[i], dy = all.y[j] - grains.y[i],
                                 dz = all.z[j] - grains.z[i];
                    double const r2 = dx * dx + dy * dy + dz * dz;
                    if (r2 == 0.0) // the target itself
                        continue;
                    double const r = std::sqrt(r2);
                    double const gm = m_G * all.m[j];
                    ax += gm * dx / (r2 * r);
                    ay += gm * dy / (r2 * r);
                    az += gm * dz / (r2 * r);
                    phi -= gm / r;
                }
            out.ax[i] = ax;
            out.ay[i] = ay;
            out.az[i] = az;
            energy += 0.5 * grains.m[i] * phi;
        }
        return m_comm.allReduce(energy, core::ReduceOp::Sum);
    }

private:
    core::Comm const& m_comm;
    double m_G;
    PairwiseOptions m_options;
};

coupling::GravityMethodEntry pairwiseSumMethod() {
    coupling::GravityMethodEntry e;
    e.name = "pairwise-sum";
    e.readKeys = [](core::ConfigTable const& gravity) -> std::any {
        PairwiseOptions o;
        o.batch = gravity.getOrIf<std::int64_t>(
            "pairwise_batch", o.batch, [](std::int64_t b) { return b > 0; },
            "a positive number of sources");
        return o;
    };
    e.make = [](coupling::GravityMethodInput const& in) {
        return std::make_unique<PairwiseSum>(in);
    };
    return e;
}

// The one line that adds the method (alike on every rank, before any run).
bool const kRegistered = (coupling::registerGravityMethod(pairwiseSumMethod()), true);

core::Comm const& world() {
    static core::Comm const comm(MPI_COMM_WORLD);
    return comm;
}

particles::SpringDashpot springDashpot() {
    particles::LinearContactParams p;
    p.stiffness = 1000.0;
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = 0.7;
    p.friction = 0.4;
    return particles::SpringDashpot(particles::MaterialTable<particles::LinearContactParams>(1, p));
}

/// 4 x 4 x 3 grains on a jittered lattice above a floor, attracting each other strongly.
/// `method` empty: no self-gravity. Every grain's position after the steps, by uid, on every
/// rank.
std::vector<Vec3> finalPositions(std::string const& method, std::any options = {}) {
    coupling::SimulationSetup s;
    s.domain.domain = core::AABB{Vec3::Zero(), Vec3::Constant(6.0)};
    s.domain.rootBlocks = {2, 2, 1};
    s.sync.reproducible = true;
    s.contact = springDashpot();
    s.dem.dt = 0.002;
    s.dem.gravity = Vec3(0.0, 0.0, -1.0);
    s.walls.add(Vec3::Zero(), Vec3::UnitZ());
    if (!method.empty()) {
        coupling::SelfGravityConfig g;
        g.method = method;
        g.G = 2.0;
        g.reproducible = true;
        g.options = std::move(options);
        s.selfGravity = g;
    }
    coupling::Simulation sim(world(), s);
    particles::Uid uid = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 3; ++k, ++uid) {
                particles::ParticleInit g;
                g.uid = uid;
                g.position = Vec3(1.2 + 1.2 * i + 0.01 * k, 1.2 + 1.2 * j, 0.7 + 1.1 * k);
                g.radius = 0.5;
                g.mass = 4.0 / 3.0 * std::numbers::pi * 0.125;
                sim.addGrain(g);
            }
    sim.start();
    sim.run(150);
    std::vector<double> flat(3 * uid, 0.0);
    sim.forEachGrain([&](particles::ParticleStorage const& ps, std::size_t i) {
        for (int a = 0; a < 3; ++a)
            flat[3 * ps.uid(i) + static_cast<std::size_t>(a)] = ps.position(i)[a];
    });
    world().allReduceInPlace(std::span<double>(flat), core::ReduceOp::Sum);
    std::vector<Vec3> out;
    for (std::size_t k = 0; k < uid; ++k)
        out.emplace_back(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
    return out;
}

double largestDistance(std::vector<Vec3> const& a, std::vector<Vec3> const& b) {
    double d = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
        d = std::max(d, (a[k] - b[k]).norm());
    return d;
}

} // namespace

TEST(GravityMethodRegistry, OwnMethodRunsAsDirect) {
    ASSERT_TRUE(kRegistered);
    auto const direct = finalPositions("direct");
    auto const own = finalPositions("pairwise-sum", PairwiseOptions{5});
    auto const none = finalPositions("");
    // The attraction moved the grains (else the comparison below would say little) ...
    EXPECT_GT(largestDistance(direct, none), 1e-2);
    // ... and the method of this file moved them as the built-in direct sum did.
    EXPECT_LT(largestDistance(own, direct), 1e-12);
    // Its own setting changes the passes, not the bits.
    auto const oneBatch = finalPositions("pairwise-sum", PairwiseOptions{1});
    EXPECT_EQ(largestDistance(own, oneBatch), 0.0);
}

TEST(GravityMethodRegistry, OwnKeysReadFromTheScene) {
    auto const& entry = coupling::gravityMethod("pairwise-sum");
    auto const scene = core::ConfigTable::fromString("[gravity]\npairwise_batch = 7\n", "s.toml");
    EXPECT_EQ(std::any_cast<PairwiseOptions>(entry.readKeys(scene.table("gravity"))).batch, 7);
    auto const bad = core::ConfigTable::fromString("[gravity]\npairwise_batch = 0\n", "s.toml");
    try {
        (void)entry.readKeys(bad.table("gravity"));
        FAIL() << "pairwise_batch = 0 accepted";
    } catch (core::InputError const& e) {
        EXPECT_STREQ(e.what(), "s.toml:2: gravity.pairwise_batch: expected a positive number of "
                               "sources, got 0");
    }
}

TEST(GravityMethodRegistry, UnknownNameListsTheRegistered) {
    try {
        (void)coupling::gravityMethod("pairwise");
        FAIL() << "an unknown method was found";
    } catch (core::InputError const& e) {
        EXPECT_STREQ(e.what(), "gravity.self = \"pairwise\": no such self-gravity method; "
                               "registered: \"direct\", \"tree\", \"pm\", \"p3m\", "
                               "\"occupied-cells\", \"tree-nodes\", \"mutual-tree\", "
                               "\"pairwise-sum\"");
    }
    coupling::SimulationSetup setup;
    setup.contact = springDashpot();
    setup.dem.dt = 1e-3;
    setup.selfGravity = coupling::SelfGravityConfig{};
    setup.selfGravity->method = "pairwise";
    try {
        coupling::Simulation const sim(world(), setup);
        FAIL() << "Simulation took an unknown method";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("registered: \"direct\""), std::string::npos)
            << e.what();
    }
}

TEST(GravityMethodRegistry, TakenNamesRefused) {
    for (char const* name : {"direct", "pairwise-sum", "none", "auto", ""}) {
        coupling::GravityMethodEntry e = pairwiseSumMethod();
        e.name = name;
        EXPECT_THROW(coupling::registerGravityMethod(e), core::Error) << name;
    }
    coupling::GravityMethodEntry noFactory;
    noFactory.name = "no-factory";
    EXPECT_THROW(coupling::registerGravityMethod(noFactory), core::Error);
    EXPECT_EQ(coupling::findGravityMethod("no-factory"), nullptr);
}
