// The collective checks: every rank throws the same InputError, and agrees on the shortest
// contact time, whichever rank holds the offending particle.
#include "core/mpi/Comm.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/validation/ParticleValidation.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::Comm;
using regolith::core::InputError;

namespace {

/// Ten grains per rank in a row along x, uids (rank, 0..9), all valid.
ParticleStorage rankSet(int rank) {
    ParticleStorage ps;
    for (int k = 0; k < 10; ++k)
        ps.add(sphere(makeUid(rank, static_cast<std::uint64_t>(k)), Vec3(k, rank, 0), 0.4, 1.0));
    return ps;
}

std::string messageOf(Comm const& world, ParticleStorage const& ps) {
    ValidationOptions o;
    try {
        validateParticles(world, ps, o);
    } catch (InputError const& e) {
        return e.what();
    }
    return {};
}

} // namespace

TEST(CollectiveValidation, EveryRankThrowsTheErrorWithTheSmallestUid) {
    Comm world;
    int const last = world.size() - 1;
    ParticleStorage ps = rankSet(world.rank());
    EXPECT_EQ(messageOf(world, ps), ""); // all valid: nobody throws

    // The last rank has a bad radius at counter 2, rank 0 a bad mass at counter 7: with one
    // rank both are on rank 0 and the radius (counter 2) wins; otherwise rank 0's uid is the
    // smaller one.
    if (world.rank() == last)
        ps.setRadius(ps.find(makeUid(last, 2)), -1.0);
    if (world.rank() == 0)
        ps.setMass(ps.find(makeUid(0, 7)), 0.0);
    std::string const m = messageOf(world, ps);
    Uid const expected = world.size() == 1 ? makeUid(0, 2) : makeUid(0, 7);
    EXPECT_NE(m.find("uid " + std::to_string(expected)), std::string::npos) << m;
    // The very same text everywhere.
    auto const all = world.gatherStrings(m, 0);
    if (world.rank() == 0) {
        for (auto const& s : all)
            EXPECT_EQ(s, m);
    }
}

TEST(CollectiveTimeStep, AllRanksAgreeOnTheShortestContactTime) {
    Comm world;
    LinearContactParams p;
    p.stiffness = 1e4;
    p.restitution = 0.5;
    SpringDashpot const model{MaterialTable<LinearContactParams>(1, p)};
    // Rank r's lightest grain has mass 1 / (r + 2): the last rank holds the global minimum.
    ParticleStorage ps = rankSet(world.rank());
    ps.setMass(3, 1.0 / (world.rank() + 2));
    ContactTimeEstimate const local = estimateContactTime(ps, model);
    ContactTimeEstimate const global = shortestContactTime(world, local);
    double const mMin = 1.0 / (world.size() + 1);
    EXPECT_NEAR(global.contactTime, SpringDashpot::undampedContactTime(p, mMin / 2), 1e-15);
    EXPECT_EQ(global.uid, makeUid(world.size() - 1, 3));
    EXPECT_EQ(global.mass, mMin);
    EXPECT_EQ(world.allReduce(global.contactTime, regolith::core::ReduceOp::Max),
              global.contactTime);
    // A rank without particles does not disturb the minimum.
    ContactTimeEstimate const none = world.rank() == 0 && world.size() > 1
                                         ? estimateContactTime(ParticleStorage{}, model)
                                         : local;
    EXPECT_EQ(shortestContactTime(world, none).uid, global.uid);
    // And every rank refuses the same dt with the same message.
    std::string msg;
    try {
        checkTimeStep(global.contactTime, global, false);
    } catch (InputError const& e) {
        msg = e.what();
    }
    EXPECT_FALSE(msg.empty());
    auto const all = world.gatherStrings(msg, 0);
    if (world.rank() == 0) {
        for (auto const& s : all)
            EXPECT_EQ(s, msg);
    }
}
