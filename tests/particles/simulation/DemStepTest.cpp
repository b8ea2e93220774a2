// DemStep, the time step over the local blocks of a rank: on 1-8 ranks and several block
// layouts, a few grains colliding across block faces, a block corner and a periodic boundary,
// sliding on a floor and bouncing off a ceiling must follow bit for bit the trajectory of the
// same grains in one block on one rank (reproducible mode), with the synchronisation
// invariants holding after every step; grains leaving an open domain are counted; NNS refuses
// a grain larger than the blocks before the first step.
#include "particles/simulation/DemStep.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/sync/SyncInvariants.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

using namespace regolith;
using namespace regolith::particles;
using core::Vec3;

namespace {

constexpr double kDt = 0.002;
constexpr int kSteps = 400;

/// One master at the end of a run, as every rank sees it after gathering.
struct FinalState {
    Uid uid = kInvalidUid;
    Vec3 x, v, w;
};

ParticleInit grain(Uid uid, Vec3 const& x, Vec3 const& v, double r = 0.5) {
    ParticleInit p;
    p.uid = uid;
    p.position = x;
    p.velocity = v;
    p.radius = r;
    p.mass = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    return p;
}

/// Domain [0, 8]^3, periodic in x and y, floor and ceiling walls, gravity -2 along z.
domain::ForestSpec boxSpec(std::array<int, 3> blocks) {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    s.rootBlocks = blocks;
    s.periodic = {true, true, false};
    return s;
}

/// The grains (radius 0.5, no initial overlap). Block faces of the 4 x 2 x 2 layout lie at
/// x = 2, 4, 6, y = 4, z = 4.
std::vector<ParticleInit> grains() {
    return {
        grain(0, {7.4, 2.0, 6.0}, {1.0, 0.0, 0.0}),  // meets 1 across the periodic x face,
        grain(1, {0.6, 2.2, 6.0}, {-1.0, 0.0, 0.0}), // off-centre: friction and spin
        grain(2, {3.5, 3.6, 4.3}, {0.5, 0.5, -0.5}), // meets 3 at the block corner (4, 4, 4)
        grain(3, {4.4, 4.3, 3.7}, {-0.5, -0.5, 0.5}),
        grain(4, {2.0, 4.0, 0.6}, {0.3, 0.0, 0.0}), // falls on the floor on a block edge
        grain(5, {6.0, 7.9, 2.0}, {0.0, 0.8, 0.0}), // crosses the periodic y face alone
        grain(6, {5.0, 1.0, 7.3}, {0.0, 0.0, 1.0}), // bounces off the ceiling
    };
}

AnyContactModel model() {
    LinearContactParams p;
    p.stiffness = 1000.0; // t_c = pi sqrt(m/2 / k) = 0.05 = 25 steps
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = 0.8;
    p.friction = 0.4;
    return SpringDashpot(MaterialTable<LinearContactParams>(1, p));
}

WallList walls() {
    WallList w;
    w.add(Vec3::Zero(), Vec3::UnitZ());
    w.add(Vec3(0.0, 0.0, 8.0), -Vec3::UnitZ());
    return w;
}

/// Every rank's masters, sorted by uid, on every rank. COLLECTIVE.
std::vector<FinalState> gatherMasters(core::Comm const& comm, LocalParticles const& local) {
    core::SendBuffer b;
    for (BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            b << bp.particles.uid(i) << bp.particles.position(i) << bp.particles.velocity(i)
              << bp.particles.angularVelocity(i);
        });
    auto const bytes = b.bytes();
    std::string const mine(reinterpret_cast<char const*>(bytes.data()), bytes.size());
    auto const parts = comm.gatherStrings(mine, 0);
    std::string all;
    for (auto const& part : parts)
        all += part;
    comm.broadcast(all, 0);
    std::vector<std::byte> data(all.size());
    std::transform(all.begin(), all.end(), data.begin(),
                   [](char c) { return static_cast<std::byte>(c); });
    core::RecvBuffer in(std::move(data));
    std::vector<FinalState> out;
    while (!in.exhausted()) {
        FinalState f;
        in >> f.uid >> f.x >> f.v >> f.w;
        out.push_back(f);
    }
    std::sort(out.begin(), out.end(),
              [](FinalState const& p, FinalState const& q) { return p.uid < q.uid; });
    return out;
}

bool sameBits(Vec3 const& a, Vec3 const& b) {
    for (int d = 0; d < 3; ++d)
        if (std::bit_cast<std::uint64_t>(a[d]) != std::bit_cast<std::uint64_t>(b[d]))
            return false;
    return true;
}

struct RunResult {
    std::vector<FinalState> masters;
    std::string violation; ///< the invariant check's message, if a sync broke an invariant
    std::uint64_t steps = 0;
    std::uint64_t contactCalls = 0;
    std::uint64_t integrateCalls = 0;
    std::size_t pairContactsListed = 0; ///< pair contacts in contacts() after the last step
};

/// Runs the scene on the ranks of `comm` with `spec`; every `completeEvery`-th step ends
/// Complete, the others Open (DemStep::StepEnd), and the run ends with completeStep().
/// COLLECTIVE.
RunResult run(core::Comm const& comm, domain::ForestSpec const& spec, SyncConfig config,
              int steps = kSteps, bool keepContacts = true, int completeEvery = 1,
              AnyIntegrator integrator = VelocityVerlet{}) {
    domain::BlockForest const forest(comm, spec);
    LocalParticles local(forest);
    for (ParticleInit const& p : grains())
        local.addMaster(p);
    ParticleSync sync(comm, forest, config);
    core::TimerTree timers;
    DemStepConfig c;
    c.dt = kDt;
    c.gravity = Vec3(0.0, 0.0, -2.0);
    c.checkInvariants = true; // after every sync: throws on every rank
    c.keepContacts = keepContacts;
    DemStep dem(comm, sync, local, model(), integrator, walls(), c, timers);
    RunResult r;
    try {
        dem.setUp();
        for (int n = 0; n < steps; ++n) {
            bool const complete = (n + 1) % completeEvery == 0;
            dem.step(complete ? DemStep::StepEnd::Complete : DemStep::StepEnd::Open);
            if (dem.stepComplete() != complete)
                r.violation = "stepComplete() after step " + std::to_string(n + 1);
            for (ContactList const& list : dem.contacts())
                r.pairContactsListed += list.pairs.size();
        }
        dem.completeStep();
    } catch (core::Error const& e) {
        r.violation = e.what();
    }
    r.masters = gatherMasters(comm, local);
    r.steps = dem.stepsDone();
    r.contactCalls = timers.calls(DemStep::kContactTimer);
    r.integrateCalls = timers.calls(DemStep::kIntegrateTimer);
    return r;
}

/// The reference: one block on one rank (MPI_COMM_SELF), computed by every rank alone.
RunResult const& serialReference() {
    static RunResult const reference = [] {
        core::Comm const self(MPI_COMM_SELF);
        SyncConfig config;
        config.reproducible = true;
        return run(self, boxSpec({1, 1, 1}), config);
    }();
    return reference;
}

void expectSameTrajectory(RunResult const& r, RunResult const& reference) {
    EXPECT_EQ(r.violation, "");
    ASSERT_EQ(r.masters.size(), reference.masters.size());
    for (std::size_t k = 0; k < r.masters.size(); ++k) {
        FinalState const& a = r.masters[k];
        FinalState const& b = reference.masters[k];
        EXPECT_EQ(a.uid, b.uid);
        EXPECT_TRUE(sameBits(a.x, b.x) && sameBits(a.v, b.v) && sameBits(a.w, b.w))
            << "uid " << a.uid << ": x " << a.x.transpose() << " vs " << b.x.transpose() << ", v "
            << a.v.transpose() << " vs " << b.v.transpose();
    }
}

} // namespace

// The reference itself does what the scene promises, so that agreeing with it means something.
TEST(DemStep, ReferenceScenePhysics) {
    RunResult const& ref = serialReference();
    EXPECT_EQ(ref.violation, "");
    ASSERT_EQ(ref.masters.size(), 7u);
    auto const& m = ref.masters;
    // 0 and 1 collided through the periodic boundary and rebounded; only they touched, and
    // gravity acts along z, so their x and y momentum (equal masses) is conserved.
    EXPECT_LT(m[0].v.x(), 0.0);
    EXPECT_GT(m[1].v.x(), 0.0);
    EXPECT_NEAR(m[0].v.x() + m[1].v.x(), 0.0, 1e-12);
    EXPECT_NEAR(m[0].v.y() + m[1].v.y(), 0.0, 1e-12);
    EXPECT_GT(m[0].w.norm(), 1e-3); // the off-centre hit with friction spun them
    // 2 and 3 collided at the block corner: their approach along (1, 1, -1) reversed.
    EXPECT_LT((m[3].v - m[2].v).dot(Vec3(-1.0, -1.0, 1.0)), 0.0);
    // 4 rests on the floor (no deeper than a few percent of its radius) and slid along x.
    EXPECT_GT(m[4].x.z(), 0.45);
    EXPECT_LT(m[4].x.z(), 0.55);
    EXPECT_GT(m[4].x.x(), 2.0);
    // 5 crossed the periodic y face and was wrapped back into the domain.
    EXPECT_LT(m[5].x.y(), 1.0);
    EXPECT_GE(m[5].x.y(), 0.0);
    // 6 bounced off the ceiling.
    EXPECT_LT(m[6].v.z(), 0.0);
    EXPECT_LT(m[6].x.z(), 7.5);
    // Set-up evaluates forces once, every step once more; the integrator runs twice a step.
    EXPECT_EQ(ref.steps, static_cast<std::uint64_t>(kSteps));
    EXPECT_EQ(ref.contactCalls, static_cast<std::uint64_t>(kSteps) + 1);
    EXPECT_EQ(ref.integrateCalls, 2 * static_cast<std::uint64_t>(kSteps));
}

TEST(DemStep, HybridOnManyBlocksEqualsOneBlock) {
    core::Comm const world;
    SyncConfig config;
    config.reproducible = true;
    expectSameTrajectory(run(world, boxSpec({4, 2, 2}), config), serialReference());
}

TEST(DemStep, EveryMethodAndLayoutEqualsOneBlock) {
    core::Comm const world;
    RunResult const& reference = serialReference();
    for (SyncMethod method :
         {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        SCOPED_TRACE(std::string(syncMethodName(method)));
        SyncConfig const config{method, true};
        // One block per rank up to 8 ranks, 8 blocks per rank, a refined forest.
        expectSameTrajectory(run(world, boxSpec({2, 2, 2}), config), reference);
        expectSameTrajectory(run(world, boxSpec({4, 4, 4}), config), reference);
        domain::ForestSpec refined = boxSpec({2, 2, 2});
        refined.refine.push_back({core::AABB{Vec3(0.0, 0.0, 0.0), Vec3(4.0, 8.0, 4.0)}, 1});
        expectSameTrajectory(run(world, refined, config), reference);
    }
}

TEST(DemStep, NotKeepingContactsChangesNothingButTheList) {
    // DemStepConfig::keepContacts = false (the driver's setting): the same bits, and no pair
    // contacts listed after the steps (the reference scene has pair contacts to list).
    core::Comm const world;
    SyncConfig config;
    config.reproducible = true;
    RunResult const kept = run(world, boxSpec({2, 2, 2}), config);
    RunResult const dropped = run(world, boxSpec({2, 2, 2}), config, kSteps, false);
    expectSameTrajectory(dropped, serialReference());
    expectSameTrajectory(kept, serialReference());
    EXPECT_EQ(dropped.pairContactsListed, 0u);
    EXPECT_GT(world.allReduce(static_cast<long long>(kept.pairContactsListed), core::ReduceOp::Sum),
              0);
}

TEST(DemStep, OpenStepsFollowTheSameTrajectory) {
    // Steps that end Open leave their second half kick to the next step's merged pass
    // (VelocityVerlet::postThenPreForce; for semi-implicit Euler postForce then preForce):
    // after completeStep() the state is that of Complete steps, bit for bit, on any layout.
    core::Comm const world;
    for (SyncMethod method : {SyncMethod::NextNeighbour, SyncMethod::Hybrid}) {
        SCOPED_TRACE(std::string(syncMethodName(method)));
        SyncConfig const config{method, true};
        expectSameTrajectory(run(world, boxSpec({2, 2, 2}), config, kSteps, false, 7),
                             serialReference());
        expectSameTrajectory(run(world, boxSpec({4, 2, 2}), config, kSteps - 1, false, kSteps),
                             run(world, boxSpec({4, 2, 2}), config, kSteps - 1));
    }
    SyncConfig const config{SyncMethod::Hybrid, true};
    expectSameTrajectory(
        run(world, boxSpec({2, 2, 2}), config, kSteps, false, 5, SemiImplicitEuler{}),
        run(world, boxSpec({2, 2, 2}), config, kSteps, false, 1, SemiImplicitEuler{}));
}

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

namespace {

/// Grains of radius 0.2 at {1, 3, 5, 7}^3 in a periodic [0, 8]^3 of 2 x 2 x 2 blocks, moving
/// along y at speed(rank that holds them) for 150 steps (at most 0.3: none leaves its block, no
/// contacts); `rebuilt(step, yes)` is called after every step with whether this rank's lists
/// were rebuilt in it. Returns this rank's list rebuilds after the set-up's. COLLECTIVE.
template <class Speed, class OnStep>
std::uint64_t runMovingLattice(core::Comm const& comm, Speed speed, OnStep&& rebuilt) {
    domain::ForestSpec spec;
    spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    spec.rootBlocks = {2, 2, 2};
    spec.periodic = {true, true, true};
    domain::BlockForest const forest(comm, spec);
    LocalParticles local(forest);
    Uid uid = 0;
    for (double x = 1.0; x < 8.0; x += 2.0)
        for (double y = 1.0; y < 8.0; y += 2.0)
            for (double z = 1.0; z < 8.0; z += 2.0)
                local.addMaster(grain(uid++, {x, y, z}, {0.0, speed(comm.rank()), 0.0}, 0.2));
    ParticleSync sync(comm, forest, SyncConfig{});
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
    return dem.listRebuilds() - setUp;
}

} // namespace

TEST(DemStep, ListsOfMovingBodiesRebuildInTheSameStep) {
    // Each rank's grains move at their own speed (1 or 0.75): the slower lists have used three
    // quarters of their skin when the faster are due, so every rank rebuilds in that step
    // (DemStep::agreeOnListRebuilds), not in turns that keep the others waiting.
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
