// coupling::Simulation, the run as a library object: the same bits on any number of ranks
// and blocks (reproducible mode), grains placed by the caller, its hooks (a body force of one's
// own, observers at the steps they ask for, velocities changed by an observer), and its refusals
// (no contact model, dt not positive, grains outside the domain or different on the ranks).
#include "coupling/simulation/Simulation.hpp"

#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

using namespace regolith;
using core::Vec3;

namespace {

coupling::SimulationSetup boxSetup(std::array<int, 3> blocks, bool selfGravity) {
    coupling::SimulationSetup s;
    s.domain.domain = core::AABB{Vec3::Zero(), Vec3::Constant(6.0)};
    s.domain.rootBlocks = blocks;
    // Self-gravity by a free-space sum needs an open domain.
    s.domain.periodic = {!selfGravity, !selfGravity, false};
    s.sync.reproducible = true;
    particles::LinearContactParams p;
    p.stiffness = 1000.0;
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = 0.7;
    p.friction = 0.4;
    s.contact =
        particles::SpringDashpot(particles::MaterialTable<particles::LinearContactParams>(1, p));
    s.dem.dt = 0.002;
    s.dem.gravity = Vec3(0.0, 0.0, -1.0);
    s.dem.keepContacts = true; // the test looks at the last step's contacts
    s.walls.add(Vec3::Zero(), Vec3::UnitZ());
    if (selfGravity) {
        coupling::SelfGravityConfig g;
        g.method = "direct";
        g.G = 0.5;
        g.reproducible = true;
        s.selfGravity = g;
    }
    return s;
}

/// 5 x 5 x 3 grains on a jittered lattice falling on the floor, given alike on every rank.
void addGrains(coupling::Simulation& sim) {
    particles::Uid uid = 0;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            for (int k = 0; k < 3; ++k, ++uid) {
                particles::ParticleInit p;
                p.uid = uid;
                p.position = Vec3(0.6 + 1.2 * i + 0.01 * k, 0.6 + 1.2 * j, 0.7 + 1.1 * k);
                p.velocity = Vec3(0.3 * ((i + k) % 3 - 1), 0.2 * ((j + 2 * k) % 3 - 1), 0.0);
                p.radius = 0.5;
                p.mass = 4.0 / 3.0 * std::numbers::pi * 0.125;
                sim.addGrain(p);
            }
}

/// A law of one's own that is the spring-dashpot: what the built-in model computes in batches,
/// through one virtual call per contact.
class ForwardedSpringDashpot final : public particles::ContactLaw {
public:
    explicit ForwardedSpringDashpot(particles::SpringDashpot model)
        : m_model(std::move(model)) {}
    particles::ContactResponse operator()(particles::ContactState const& s, Vec3& spring,
                                          Vec3& rolling, double dt) const override {
        return m_model(s, spring, rolling, dt);
    }
    double contactTime(std::uint32_t a, std::uint32_t b, double mass) const override {
        return particles::SpringDashpot::undampedContactTime(m_model.materials()(a, b), mass);
    }

private:
    particles::SpringDashpot m_model;
};

struct Final {
    particles::Uid uid;
    std::uint64_t x, v;
};

/// Every grain's x and v_x bits, sorted by uid, on every rank. COLLECTIVE.
std::vector<Final> finalState(coupling::Simulation& sim) {
    std::vector<double> mine(75 * 2, 0.0);
    sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        mine[2 * g.uid(i)] = g.position(i).x() + g.position(i).y() + g.position(i).z();
        mine[2 * g.uid(i) + 1] = g.velocity(i).x();
    });
    sim.comm().allReduceInPlace(std::span<double>(mine), core::ReduceOp::Sum);
    std::vector<Final> out;
    for (particles::Uid u = 0; u < 75; ++u)
        out.push_back({u, std::bit_cast<std::uint64_t>(mine[2 * u]),
                       std::bit_cast<std::uint64_t>(mine[2 * u + 1])});
    return out;
}

std::vector<Final> runOn(core::Comm const& comm, std::array<int, 3> blocks, bool selfGravity,
                         bool ownLaw = false) {
    coupling::SimulationSetup setup = boxSetup(blocks, selfGravity);
    if (ownLaw)
        if (auto const* linear = setup.contact->get<particles::SpringDashpot>())
            setup.contact =
                particles::CustomContact(std::make_shared<ForwardedSpringDashpot>(*linear));
    coupling::Simulation sim(comm, setup);
    addGrains(sim);
    sim.start();
    sim.run(400);
    // The grains touch each other at the end (else the equality below would say little).
    std::size_t pairs = 0;
    for (particles::ContactList const& list : sim.dem().contacts())
        pairs += list.pairs.size();
    EXPECT_GT(comm.allReduce(pairs, core::ReduceOp::Sum), 0u);
    return finalState(sim);
}

std::string errorOf(auto&& f) {
    try {
        f();
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(Simulation, SameBitsOnAnyRanksAndBlocksAsOneBlockOnOneRank) {
    core::Comm const world;
    core::Comm const self(MPI_COMM_SELF);
    for (bool gravity : {false, true}) {
        SCOPED_TRACE(gravity ? "with self-gravity" : "contacts only");
        std::vector<Final> const reference = runOn(self, {1, 1, 1}, gravity);
        for (std::array<int, 3> blocks : {std::array{1, 1, 1}, std::array{3, 3, 2}}) {
            std::vector<Final> const run = runOn(world, blocks, gravity);
            for (std::size_t k = 0; k < reference.size(); ++k) {
                EXPECT_EQ(run[k].x, reference[k].x) << "uid " << k;
                EXPECT_EQ(run[k].v, reference[k].v) << "uid " << k;
            }
        }
    }
}

TEST(Simulation, GrainsPlacedByTheCallerGiveTheBitsOfGrainsGivenAlike) {
    core::Comm const world;
    core::Comm const self(MPI_COMM_SELF);
    std::vector<Final> const reference = runOn(self, {1, 1, 1}, true);
    coupling::SimulationSetup setup = boxSetup({3, 3, 2}, true);
    setup.dem.keepContacts = false;
    // Each rank keeps its own grains, on blocks of equal weight (not balanced by the grains).
    coupling::Placement placed = coupling::placeBlocks(world, setup.domain, {}, setup.subdomains);
    coupling::Simulation given(self, boxSetup({1, 1, 1}, true));
    addGrains(given); // only to read the grains back below
    coupling::Simulation sim(world, setup, std::move(placed));
    EXPECT_THROW(sim.addGrain(particles::ParticleInit{}), core::Error);
    given.start();
    given.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        particles::ParticleInit p;
        p.uid = g.uid(i);
        p.position = g.position(i);
        p.velocity = g.velocity(i);
        p.radius = g.radius(i);
        p.mass = g.mass(i);
        (void)sim.placement().local->addMaster(p);
    });
    // The contacts are kept for the observer that asks for them, at its steps only.
    std::vector<std::size_t> pairsSeen;
    sim.addObserver([](std::int64_t step) { return step % 200 == 0; },
                    [&](coupling::Simulation& s) {
                        std::size_t pairs = 0;
                        for (particles::ContactList const& list : s.dem().contacts())
                            pairs += list.pairs.size();
                        pairsSeen.push_back(world.allReduce(pairs, core::ReduceOp::Sum));
                    },
                    {.completeGrains = true, .contacts = true});
    sim.start();
    sim.run(400);
    ASSERT_EQ(pairsSeen.size(), 2u);
    EXPECT_GT(pairsSeen[1], 0u);
    std::vector<Final> const run = finalState(sim);
    for (std::size_t k = 0; k < reference.size(); ++k) {
        EXPECT_EQ(run[k].x, reference[k].x) << "uid " << k;
        EXPECT_EQ(run[k].v, reference[k].v) << "uid " << k;
    }
}

TEST(Simulation, ALawOfOnesOwnGivesTheBitsOfTheBuiltInModelItForwardsTo) {
    core::Comm const world;
    std::vector<Final> const builtIn = runOn(world, {3, 3, 2}, false);
    std::vector<Final> const own = runOn(world, {3, 3, 2}, false, true);
    for (std::size_t k = 0; k < builtIn.size(); ++k) {
        EXPECT_EQ(own[k].x, builtIn[k].x) << "uid " << k;
        EXPECT_EQ(own[k].v, builtIn[k].v) << "uid " << k;
    }
}

TEST(Simulation, BodyForcesAndObserversRunWhenAsked) {
    core::Comm const world;
    coupling::SimulationSetup setup = boxSetup({2, 2, 2}, false);
    setup.dem.gravity = Vec3::Zero();
    setup.walls = particles::WallList{};
    coupling::Simulation sim(world, setup);
    particles::ParticleInit lone;
    lone.uid = 7;
    lone.position = Vec3(3.0, 3.0, 3.0);
    lone.radius = 0.5;
    lone.mass = 2.0;
    sim.addGrain(lone);
    // A force of 1 along x on every master: a = 1 / m = 0.5.
    sim.addBodyForces([](particles::LocalParticles& grains) {
        for (particles::BlockParticles& b : grains.blocks())
            b.particles.forEachMaster([&](std::size_t i) { b.particles.force(i).x() += 1.0; });
    });
    std::vector<std::int64_t> seen;
    sim.addObserver(40, [&](coupling::Simulation& s) { seen.push_back(s.stepsDone()); });
    // An observer may change velocities: stop the grain along y after step 50.
    sim.addObserver(50, [](coupling::Simulation& s) {
        s.forEachGrain(
            [](particles::ParticleStorage& g, std::size_t i) { g.velocity(i).y() = 0.0; });
    });
    sim.start();
    sim.forEachGrain([](particles::ParticleStorage& g, std::size_t i) { g.velocity(i).y() = 1.0; });
    sim.run(130);
    EXPECT_EQ(seen, (std::vector<std::int64_t>{40, 80, 120}));
    EXPECT_DOUBLE_EQ(sim.time(), 130 * 0.002);
    double vx = 0.0, vy = 0.0;
    sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        vx = g.velocity(i).x();
        vy = g.velocity(i).y();
    });
    vx = world.allReduce(vx, core::ReduceOp::Sum);
    vy = world.allReduce(vy, core::ReduceOp::Sum); // 1 had the observer not stopped it
    EXPECT_NEAR(vx, 0.5 * sim.time(), 1e-12);
    EXPECT_EQ(vy, 0.0);
}

TEST(Simulation, RefusesWhatCannotRun) {
    core::Comm const world;
    coupling::SimulationSetup noContact = boxSetup({1, 1, 1}, false);
    noContact.contact.reset();
    EXPECT_NE(errorOf([&] { coupling::Simulation sim(world, noContact); }).find("contact model"),
              std::string::npos);
    coupling::SimulationSetup noDt = boxSetup({1, 1, 1}, false);
    noDt.dem.dt = 0.0;
    EXPECT_NE(errorOf([&] { coupling::Simulation sim(world, noDt); }).find("expected dt > 0"),
              std::string::npos);

    std::string const outside = errorOf([&] {
        coupling::Simulation sim(world, boxSetup({2, 2, 2}, false));
        particles::ParticleInit p;
        p.uid = 1;
        p.position = Vec3(3.0, 3.0, 9.0); // above the box (z is not periodic)
        p.radius = 0.5;
        p.mass = 1.0;
        sim.addGrain(p);
        sim.start();
    });
    EXPECT_NE(outside.find("1 of 1 grains lie outside the domain"), std::string::npos) << outside;

    // The time-step guard asks a law of one's own for its contact time.
    std::string const tooLong = errorOf([&] {
        coupling::SimulationSetup setup = boxSetup({2, 2, 2}, false);
        if (auto const* linear = setup.contact->get<particles::SpringDashpot>())
            setup.contact =
                particles::CustomContact(std::make_shared<ForwardedSpringDashpot>(*linear));
        setup.dem.dt = 0.01; // t_c = pi sqrt(m / 2k) = 0.036
        coupling::Simulation sim(world, setup);
        addGrains(sim);
        sim.start();
    });
    EXPECT_NE(tooLong.find("exceeds t_c/10"), std::string::npos) << tooLong;
    EXPECT_NE(tooLong.find("the contact law's contactTime"), std::string::npos) << tooLong;

    if (world.size() > 1) {
        std::string const different = errorOf([&] {
            coupling::Simulation sim(world, boxSetup({2, 2, 2}, false));
            if (world.rank() == 0)
                addGrains(sim);
            sim.start();
        });
        EXPECT_NE(different.find("different numbers of grains"), std::string::npos) << different;
        // The same count, one grain a hair apart on the last rank (a rank-seeded start).
        std::string const moved = errorOf([&] {
            coupling::Simulation sim(world, boxSetup({2, 2, 2}, false));
            particles::ParticleInit p;
            p.uid = 1;
            p.position = Vec3(3.0, 3.0, world.rank() + 1 == world.size() ? 3.01 : 3.0);
            p.radius = 0.5;
            p.mass = 1.0;
            sim.addGrain(p);
            sim.start();
        });
        EXPECT_NE(moved.find("the ranks were given different grains"), std::string::npos) << moved;
    }

    // The gravity method's limits, as the scene driver checks them.
    coupling::SimulationSetup softened = boxSetup({1, 1, 1}, true);
    softened.selfGravity->method = "tree-nodes";
    softened.selfGravity->softening = 0.1;
    EXPECT_NE(errorOf([&] {
                  coupling::Simulation sim(world, softened);
              }).find("\"tree-nodes\" does not soften, but SelfGravityConfig::softening = 0.1"),
              std::string::npos);
    coupling::SimulationSetup periodic = boxSetup({1, 1, 1}, true);
    periodic.domain.periodic = {true, false, true};
    EXPECT_NE(errorOf([&] { coupling::Simulation sim(world, periodic); })
                  .find("\"direct\" sums in free space, without periodic images, but "
                        "SimulationSetup::domain.periodic makes x, z periodic"),
              std::string::npos);
}
