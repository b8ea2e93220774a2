// The tangential springs the Verlet lists keep beside their pairs deep inside a block
// (ContactDetector, "Springs kept beside the list"; DemStepConfig::keepSprings): a packing that
// starts compressed, flies apart, falls and settles, on several block layouts and ranks, with
// mostly Open steps (the springs stay beside the lists across steps and are written back
// before syncs that may migrate a grain, at Complete steps and at the end), must end with the
// same bits as the run that keeps every spring in the grains' histories: positions,
// velocities, spins, and every live history entry.
#include "tests/particles/simulation/KeptSpringsHarness.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <gtest/gtest.h>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::kept_springs;

namespace {

TEST(KeptSprings, ChangeNoBitOnAnyLayout) {
    core::Comm const world;
    for (bool reproducible : {true, false}) {
        for (std::array<int, 3> blocks :
             {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{1, 3, 1}, std::array<int, 3>{2, 2, 1},
              std::array<int, 3>{3, 2, 2}}) {
            SCOPED_TRACE(::testing::Message() << "reproducible " << reproducible << ", blocks "
                                              << blocks[0] << "x" << blocks[1] << "x" << blocks[2]);
            SyncConfig const config{SyncMethod::Hybrid, reproducible};
            expectSameBits(world, packing(blocks), config);
            // Every neighbour overlapping by 0.2, more than the skin (0.15): evaluated untested
            // while listed (PairMode::KeptPressed), until the packing flies apart.
            expectSameBits(world, packing(blocks, 0.3, 0.6), config);
            // The skin chosen for the scene: the overlapping packing lists its six neighbours
            // with a wider one (and rebuilds less often).
            Scene wider = packing(blocks, 0.3, 0.6);
            wider.skinForTheScene = true;
            expectSameState(run(world, wider, config, true), run(world, wider, config, false),
                            wider.grains.size());
        }
    }
}

TEST(KeptSprings, ChangeNoBitWhileContactsOutliveRebuilds) {
    // A pressed packing sliding down a ramp along x and y (as scene B's): its lists are rebuilt
    // every few steps while most contacts last, pairs cross block faces and come near them, and
    // every rebuild's kept springs must come back whole from the previous list's.
    core::Comm const world;
    for (std::array<int, 3> blocks : {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{3, 2, 2}}) {
        SCOPED_TRACE(::testing::Message()
                     << "blocks " << blocks[0] << "x" << blocks[1] << "x" << blocks[2]);
        Scene sliding = packing(blocks, 0.05, 0.52);
        sliding.gravity = Vec3(6.0, 3.0, -2.0);
        for (ParticleInit& g : sliding.grains)
            g.velocity += Vec3(1.0, 0.5, 0.0);
        sliding.steps = 200;
        Outcome const kept = run(world, sliding, SyncConfig{SyncMethod::Hybrid, false}, true);
        expectSameBits(kept, run(world, sliding, SyncConfig{SyncMethod::Hybrid, false}, false),
                       sliding.grains.size());
        // Mostly shifted with the drift (ContactDetector::beforeSync), sometimes rebuilt.
        EXPECT_GT(kept.shifts, 10);
        EXPECT_GT(kept.rebuilds, 0);
        // The contacts of the shifted lists are those of a linked-cell pass every step: the
        // same bits where the forces are summed by uid.
        SyncConfig const reproducible{SyncMethod::Hybrid, true};
        Scene cells = sliding;
        cells.listed = false;
        Outcome const shifted = run(world, sliding, reproducible, true);
        expectSameState(shifted, run(world, cells, reproducible, false), sliding.grains.size());
        EXPECT_GT(shifted.shifts, 10);
    }
}

TEST(KeptSprings, ChangeNoBitWithContactsKeptOrSortedByUid) {
    // Kept contacts: the list hands each contact found, with its kept spring. Sorted by uid:
    // contacts are handed over after the sort, with the histories (the springs stay there).
    core::Comm const world;
    for (double r : {kRadius, 0.6}) {
        SCOPED_TRACE(::testing::Message() << "radius " << r);
        Scene kept = packing({2, 2, 1}, 0.3, r);
        kept.keepContacts = true;
        expectSameBits(world, kept, SyncConfig{SyncMethod::Hybrid, false});
        Scene sorted = packing({2, 2, 1}, 0.3, r);
        sorted.sortByUid = true;
        expectSameBits(world, sorted, SyncConfig{SyncMethod::Hybrid, false});
    }
}

TEST(KeptSprings, ChangeNoBitWhenAStepOutrunsTheSkin) {
    // A skin of 0.01 and steps of 0.005: a colliding pair, settled deeper than the half skin
    // inside its block, crosses the block face x = 2 in one step during the contact, in the
    // synchronisation before any list notices: its spring, grown by the sliding (relative
    // velocity 0.3 along x) since the last rebuild, must be back in its history before
    // (DemStep: ContactDetector::beforeSync). Contact from step ~8 to ~19, the face at ~14.
    core::Comm const world;
    Scene pair;
    pair.spec.domain = core::AABB{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
    pair.spec.rootBlocks = {3, 1, 1};
    pair.grains = {synctest::grain(1, Vec3(1.71, 3.0, 3.0), kRadius, Vec3(4.0, 0.0, 0.0)),
                   synctest::grain(2, Vec3(1.71, 4.03, 3.0), kRadius, Vec3(4.3, -0.5, 0.0))};
    pair.walls = false;
    pair.gravity = Vec3::Zero();
    pair.dt = 0.005;
    pair.skin = 0.01;
    pair.steps = 16; // ends during the contact
    expectSameBits(world, pair, SyncConfig{SyncMethod::Hybrid, false});
    Scene fast = packing({3, 2, 2}, 3.0);
    fast.dt = 0.005;
    fast.skin = 0.01;
    expectSameBits(world, fast, SyncConfig{SyncMethod::Hybrid, false});
}

TEST(KeptSprings, ChangeNoBitWhenARebuildKeepsNoPair) {
    // A sticking pair drifting towards the face x = 2 of its block, and a lone grain whose
    // motion rebuilds the block's list every few steps: the pair's contact starts after a
    // rebuild that kept the pair (no history entry yet: the spring lives beside the list only),
    // and a later rebuild during the contact finds it closer to the face than skin / 2, so the
    // new list keeps no pair at all. The carried spring must still reach the history, as the
    // last pass stamped it. Start positions swept so that the rebuilds fall at every phase.
    core::Comm const world;
    for (int k = 0; k < 12; ++k) {
        double const x = 1.93 + 0.0025 * k;
        SCOPED_TRACE(::testing::Message() << "x " << x);
        Scene pair;
        pair.spec.domain = core::AABB{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
        pair.spec.rootBlocks = {3, 1, 1};
        pair.grains = {synctest::grain(1, Vec3(x, 3.0, 3.0), kRadius, Vec3(0.5, 0.0, 0.0)),
                       synctest::grain(2, Vec3(x, 4.03, 3.0), kRadius, Vec3(0.6, -0.5, 0.0)),
                       synctest::grain(3, Vec3(1.0, 1.0, 2.0), kRadius, Vec3(0.0, 0.0, 2.0))};
        pair.walls = false;
        pair.gravity = Vec3::Zero();
        pair.dt = 0.005;
        pair.skin = 0.04;
        pair.steps = 16; // ends during the contact (from step ~8)
        expectSameBits(world, pair, SyncConfig{SyncMethod::Hybrid, false});
    }
}

} // namespace
