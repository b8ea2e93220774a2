// The kept springs carried from a Verlet list to the one rebuilt after it (ContactDetector,
// "Springs carried across a rebuild"): a pressed packing sliding down a ramp, whose contacts
// outlive many rebuilds, must end with the same bits as the run that keeps every spring in the
// grains' histories, on several block layouts and ranks, whether the rebuilt list takes a
// carried spring or writes it back because it no longer keeps the pair.
#include "tests/particles/simulation/KeptSpringsRun.hpp"

#include <gtest/gtest.h>

#include <array>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::keptspringstest;
using core::Vec3;

namespace {

/// The packing pressed (every neighbour overlapping by 0.04), sliding along x and y under a
/// tilted gravity: the lists are rebuilt every few steps while the contacts last, and pairs
/// cross the block faces (and, with more than one block along an axis, come near one while
/// still inside: the rebuilt list no longer keeps their springs).
Scene slidingPack(std::array<int, 3> blocks) {
    Scene s = packing(blocks, 0.05, 0.52);
    s.gravity = Vec3(6.0, 3.0, -2.0);
    for (ParticleInit& g : s.grains)
        g.velocity += Vec3(1.0, 0.5, 0.0);
    s.steps = 200;
    s.completeEvery = 1000; // only Open steps: the springs stay beside the lists
    return s;
}

TEST(CarriedSprings, ChangeNoBitAcrossRebuilds) {
    core::Comm const world;
    for (bool reproducible : {true, false}) {
        for (std::array<int, 3> blocks :
             {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{3, 2, 1}}) {
            SCOPED_TRACE(::testing::Message() << "reproducible " << reproducible << ", blocks "
                                              << blocks[0] << "x" << blocks[1] << "x" << blocks[2]);
            Scene const scene = slidingPack(blocks);
            SyncConfig const config{SyncMethod::Hybrid, reproducible};
            Outcome const kept = run(world, scene, config, true);
            Outcome const histories = run(world, scene, config, false);
            expectSameBits(kept, histories, scene.grains.size());
            EXPECT_GT(kept.rebuilds, 10);
            // Most springs go from list to list: a lost or stale one changes the bits above.
            EXPECT_GT(kept.carried, kept.keptMost);
            EXPECT_EQ(histories.carried, 0);
        }
    }
}

TEST(CarriedSprings, ThoseTheRebuiltListDoesNotKeepReachTheHistories) {
    // Pairs that stay in their block through the synchronisation but lie too near a block face
    // for the rebuilt list to keep their springs: carried, then written back before the pass,
    // which reads them from the histories.
    core::Comm const world;
    for (bool reproducible : {true, false}) {
        SCOPED_TRACE(::testing::Message() << "reproducible " << reproducible);
        Scene const scene = slidingPack({3, 2, 2});
        SyncConfig const config{SyncMethod::Hybrid, reproducible};
        Outcome const kept = run(world, scene, config, true);
        Outcome const histories = run(world, scene, config, false);
        expectSameBits(kept, histories, scene.grains.size());
        EXPECT_GT(kept.carriedBack, 0);
        EXPECT_GT(kept.carried, kept.carriedBack);
    }
}

} // namespace
