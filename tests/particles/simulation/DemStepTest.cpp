// DemStep, the time step over the local blocks of a rank: on 1-8 ranks and several block
// layouts, a few grains colliding across block faces, a block corner and a periodic boundary,
// sliding on a floor and bouncing off a ceiling must follow bit for bit the trajectory of the
// same grains in one block on one rank (reproducible mode), with the synchronisation
// invariants holding after every step, also when steps end Open or the contacts are not kept.
// Around the synchronisation: DemStepSyncTest.cpp.
#include "particles/simulation/DemStep.hpp"

#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "tests/particles/simulation/DemStepScene.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::demsteptest;
using core::Vec3;

namespace {

constexpr int kSteps = 400;

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

WallList walls() {
    WallList w;
    w.add(Vec3::Zero(), Vec3::UnitZ());
    w.add(Vec3(0.0, 0.0, 8.0), -Vec3::UnitZ());
    return w;
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
