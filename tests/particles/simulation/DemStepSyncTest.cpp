// DemStep around the synchronisation, on 1-8 ranks: grains leaving an open domain are counted
// and leave no copy behind; NNS refuses a grain larger than the blocks before the first step; a
// bad time step is refused; the ranks rebuild their Verlet lists in the same step (the same
// steps where the agreement on it is skipped), and lists at rest are not rebuilt for others; the
// body forces' vote is the maximum over the ranks.
#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/SyncInvariants.hpp"
#include "tests/particles/simulation/DemStepScene.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::demsteptest;
using core::Vec3;

namespace {

/// Grains of radius 0.2 at {1, 3, 5, 7}^3 in a periodic [0, 8]^3 of 2 x 2 x 2 blocks, moving
/// along y at speed(rank that holds them) for 150 steps (at most 0.3: none leaves its block, no
/// contacts), every other one (by uid) backwards unless `drift` (then the lists shift with the
/// grains instead of rebuilding); `rebuilt(step, yes)` is called after every step with whether
/// this rank's lists were rebuilt in it; `syncSkin`: SyncConfig::skin. Returns this rank's
/// list rebuilds after the set-up's, and its shifts in `shifts`. COLLECTIVE.
template <class Speed, class OnStep>
std::uint64_t runMovingLattice(core::Comm const& comm, Speed speed, OnStep&& rebuilt,
                               double syncSkin = 0.0, bool drift = false,
                               std::uint64_t* shifts = nullptr) {
    domain::ForestSpec spec;
    spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    spec.rootBlocks = {2, 2, 2};
    spec.periodic = {true, true, true};
    domain::BlockForest const forest(comm, spec);
    LocalParticles local(forest);
    Uid uid = 0;
    for (double x = 1.0; x < 8.0; x += 2.0)
        for (double y = 1.0; y < 8.0; y += 2.0)
            for (double z = 1.0; z < 8.0; z += 2.0, ++uid) {
                double const v = (drift || uid % 2 == 0 ? 1.0 : -1.0) * speed(comm.rank());
                local.addMaster(grain(uid, {x, y, z}, {0.0, v, 0.0}, 0.2));
            }
    ParticleSync sync(comm, forest, SyncConfig{.skin = syncSkin});
    core::TimerTree timers;
    DemStepConfig c;
    c.dt = kDt;
    DemStep dem(comm, sync, local, model(), VelocityVerlet{}, WallList{}, c, timers);
    dem.setUp();
    std::uint64_t const setUp = dem.listRebuilds();
    for (int n = 0; n < 150; ++n) {
        std::uint64_t const before = dem.listRebuilds();
        dem.step();
        rebuilt(n + 1, dem.listRebuilds() > before);
    }
    if (shifts != nullptr)
        *shifts = dem.listShifts();
    return dem.listRebuilds() - setUp;
}

} // namespace

TEST(DemStep, GrainsLeavingAnOpenDomainAreCounted) {
    core::Comm const world;
    domain::ForestSpec spec;
    spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    spec.rootBlocks = {2, 2, 2};
    domain::BlockForest const forest(world, spec);
    LocalParticles local(forest);
    // Two grains fly out through x = 8 and y = 0 (no walls, no periodicity); one stays.
    for (ParticleInit const& p :
         {grain(1, {7.7, 4.1, 4.1}, {1.0, 0.0, 0.0}), grain(2, {3.9, 0.4, 2.0}, {0.0, -1.0, 0.0}),
          grain(3, {3.0, 3.0, 3.0}, {0.1, 0.0, 0.0})})
        local.addMaster(p);
    ParticleSync sync(world, forest, SyncConfig{});
    core::TimerTree timers;
    DemStepConfig c;
    c.dt = 0.01;
    DemStep dem(world, sync, local, model(), VelocityVerlet{}, WallList{}, c, timers);
    dem.setUp();
    EXPECT_EQ(world.allReduce(static_cast<long long>(dem.leftDomain()), core::ReduceOp::Sum), 0);
    for (int n = 0; n < 100; ++n) // 1 length unit: both are beyond the faces by 0.1 + radius
        dem.step();
    EXPECT_EQ(world.allReduce(static_cast<long long>(dem.leftDomain()), core::ReduceOp::Sum), 2);
    EXPECT_EQ(world.allReduce(static_cast<long long>(local.countMasters()), core::ReduceOp::Sum),
              1);
    // No copy of the departed grains is left anywhere (3 stays inside its block).
    EXPECT_EQ(world.allReduce(static_cast<long long>(local.countCopies()), core::ReduceOp::Sum), 1);
    auto const masters = gatherMasters(world, local);
    ASSERT_EQ(masters.size(), 1u);
    EXPECT_EQ(masters[0].uid, 3u);
    EXPECT_TRUE(checkSyncInvariants(local, world, true).empty());
}

TEST(DemStep, SetUpRefusesAGrainTooLargeForNns) {
    core::Comm const world;
    domain::ForestSpec spec;
    spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    spec.rootBlocks = {4, 4, 4}; // edge 2
    spec.periodic = {true, true, true};
    domain::BlockForest const forest(world, spec);
    for (SyncMethod method :
         {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        SCOPED_TRACE(std::string(syncMethodName(method)));
        LocalParticles local(forest);
        local.addMaster(grain(7, {4.1, 4.2, 4.3}, Vec3::Zero(), 2.5));
        local.addMaster(grain(8, {0.5, 0.5, 0.5}, Vec3::Zero(), 0.4));
        ParticleSync sync(world, forest, SyncConfig{method, false});
        core::TimerTree timers;
        DemStepConfig c;
        c.dt = 0.01;
        DemStep dem(world, sync, local, model(), VelocityVerlet{}, WallList{}, c, timers);
        if (method == SyncMethod::NextNeighbour) {
            std::string message;
            try {
                dem.setUp();
            } catch (core::InputError const& e) {
                message = e.what();
            }
            EXPECT_NE(message.find("particle uid 7 has radius 2.5"), std::string::npos) << message;
            EXPECT_NE(message.find("sync.method = \"sos\" or \"hybrid\""), std::string::npos)
                << message;
            continue;
        }
        EXPECT_GE(dem.setUp(), 2); // the large grain spreads one block layer per call
        dem.step();
        EXPECT_TRUE(checkSyncInvariants(local, world, true).empty());
    }
}

TEST(DemStep, RejectsABadTimeStep) {
    core::Comm const world;
    domain::ForestSpec spec;
    domain::BlockForest const forest(world, spec);
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{});
    core::TimerTree timers;
    for (double dt : {0.0, -1.0, std::nan("")}) {
        DemStepConfig c;
        c.dt = dt;
        EXPECT_THROW(DemStep(world, sync, local, model(), VelocityVerlet{}, WallList{}, c, timers),
                     core::Error);
    }
}

TEST(DemStep, ListsOfMovingBodiesRebuildInTheSameStep) {
    // Each rank's grains move at their own speed (1 or 0.75): the slower lists have used three
    // quarters of their skin when the faster are due, so every rank rebuilds in that step
    // (DemStep::agreeAfterSync), not in turns that keep the others waiting.
    core::Comm const world;
    int disagreements = 0;
    std::uint64_t const rebuilds = runMovingLattice(
        world, [](int rank) { return rank % 2 == 0 ? 1.0 : 0.75; },
        [&](int step, bool rebuilt) {
            int const here = rebuilt ? 1 : 0;
            if (world.allReduce(here, core::ReduceOp::Min) !=
                world.allReduce(here, core::ReduceOp::Max)) {
                ++disagreements;
                ADD_FAILURE() << "step " << step << ": rank " << world.rank() << " rebuilt "
                              << rebuilt;
            }
        });
    EXPECT_EQ(disagreements, 0);
    EXPECT_GE(rebuilds, 2u) << "the lists must be rebuilt while moving for the test to mean much";
}

TEST(DemStep, StepsWithoutTheRebuildAgreementRebuildAsWithIt) {
    // With a sync skin the sync goes along its list (no storage changes), so in the steps
    // whose motion stays within every list's quiet motion the ranks skip the agreement after
    // the sync (StepAgreement.hpp); without one they agree every step. The same rebuilds.
    core::Comm const world;
    auto const speed = [](int rank) { return rank % 2 == 0 ? 1.0 : 0.75; };
    std::vector<int> every, skipping;
    runMovingLattice(world, speed, [&](int, bool rebuilt) { every.push_back(rebuilt); });
    std::uint64_t const rebuilds = runMovingLattice(
        world, speed, [&](int, bool rebuilt) { skipping.push_back(rebuilt); }, 0.05);
    EXPECT_EQ(skipping, every);
    EXPECT_GE(rebuilds, 2u);
}

TEST(DemStep, ListsAtRestAreNotRebuiltForOthers) {
    // Only rank 0's grains move: the other ranks' lists, which used none of their skin, keep
    // their set-up's list however often rank 0 rebuilds.
    core::Comm const world;
    std::uint64_t const rebuilds = runMovingLattice(
        world, [](int rank) { return rank == 0 ? 1.0 : 0.0; }, [](int, bool) {});
    if (world.rank() == 0)
        EXPECT_GE(rebuilds, 2u);
    else
        EXPECT_EQ(rebuilds, 0u);
}

TEST(DemStep, ListsOfADriftingLatticeShiftInsteadOfRebuilding) {
    // Every grain of a rank at the same velocity: its lists follow the drift by shifting their
    // references (ContactDetector::beforeSync), none is rebuilt after the set-up.
    core::Comm const world;
    std::uint64_t shifts = 0;
    std::uint64_t const rebuilds = runMovingLattice(
        world, [](int rank) { return rank % 2 == 0 ? 1.0 : 0.75; }, [](int, bool) {}, 0.0, true,
        &shifts);
    EXPECT_EQ(rebuilds, 0u);
    EXPECT_GE(shifts, 2u);
}

TEST(DemStep, BodyForceVoteIsTheMaximumOverRanks) {
    // Each rank votes (rank, -rank): every force computation's body forces see (size - 1, 0)
    // on every rank, one share per computation, taken before the contacts.
    core::Comm const world;
    domain::BlockForest const forest(world, boxSpec({2, 2, 2}));
    LocalParticles local(forest);
    Uid uid = 0;
    for (double x = 1.0; x < 8.0; x += 2.0)
        local.addMaster(grain(uid++, {x, 1.0, 1.0}, {0.0, 1.0, 0.0}, 0.2));
    ParticleSync sync(world, forest, SyncConfig{});
    core::TimerTree timers;
    DemStepConfig c;
    c.dt = kDt;
    DemStep dem(world, sync, local, model(), VelocityVerlet{}, WallList{}, c, timers);
    int shares = 0, applied = 0;
    dem.setBodyForceVote([&](LocalParticles const&) {
        ++shares;
        return std::array<double, 2>{static_cast<double>(world.rank()),
                                     -static_cast<double>(world.rank())};
    });
    dem.setBodyForces([&](LocalParticles&) {
        ++applied;
        EXPECT_EQ(dem.bodyForceVote()[0], static_cast<double>(world.size() - 1));
        EXPECT_EQ(dem.bodyForceVote()[1], 0.0);
    });
    dem.setUp();
    for (int n = 0; n < 5; ++n)
        dem.step();
    EXPECT_EQ(applied, 6);
    EXPECT_EQ(shares, applied);
}
