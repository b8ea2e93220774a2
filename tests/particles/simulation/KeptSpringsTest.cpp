// The tangential springs the Verlet lists keep beside their pairs deep inside a block
// (ContactDetector, "Springs kept beside the list"; DemStepConfig::keepSprings): a packing that
// starts compressed, flies apart, falls and settles, on several block layouts and ranks, with
// mostly Open steps (the springs stay beside the lists across steps and are written back
// before syncs that may migrate a grain, at Complete steps and at the end), must end with the
// same bits as the run that keeps every spring in the grains' histories: positions,
// velocities, spins, and every live history entry.
#include "tests/particles/simulation/KeptSpringsRun.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::keptspringstest;
using core::Vec3;

namespace {

TEST(KeptSprings, ChangeNoBitOnAnyLayout) {
    core::Comm const world;
    for (bool reproducible : {true, false}) {
        for (std::array<int, 3> blocks : {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{2, 2, 1},
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

TEST(KeptSprings, FacePairsOfAWholeDomainBlockChangeNoBit) {
    // One block holding the whole periodic domain settles the instance of each pair across a
    // periodic face whose i is i's master, and drops its twin (ContactDetector, "Pairs across a
    // periodic face"); blocks that tile the domain settle none. In reproducible mode the two
    // layouts must end with the same bits: a face contact doubled or missed shows. A drift
    // carries the grains across the x and y faces while they touch: settled face pairs die as
    // grains wrap (their kept springs go back to the grains' copies by uid), and twins arrive
    // as grains start to cross a face (drifting down x and y: the lower uid of a face pair,
    // near the lower face, moves towards it), to be dropped while the settled pair lives.
    core::Comm const world;
    for (bool keep : {true, false}) {
        for (double r : {kRadius, 0.6}) {
            for (double drift : {2.0, -2.0}) {
                SCOPED_TRACE(::testing::Message()
                             << "springs kept " << keep << ", radius " << r << ", drift " << drift);
                Scene one = packing({1, 1, 1}, 0.3, r);
                Scene tiled = packing({3, 2, 1}, 0.3, r);
                for (Scene* s : {&one, &tiled})
                    for (ParticleInit& g : s->grains)
                        g.velocity += Vec3(drift, 0.65 * drift, 0.0);
                SyncConfig const config{SyncMethod::Hybrid, true};
                Outcome const a = run(world, one, config, keep);
                Outcome const b = run(world, tiled, config, keep);
                EXPECT_GT(a.twinsMost, 0);
                EXPECT_EQ(b.twinsMost, 0);
                expectSameState(a, b, one.grains.size());
            }
        }
    }
}

TEST(KeptSprings, AFacePairsTwinArrivingWhileItLivesIsDropped) {
    // A small grain i (lower uid) touches a large grain j's image across the face x = 0 at a
    // slant, the two drifting towards -x together: the list settles (i's master, j's image)
    // while i's ball does not reach the face, as j's image reaches deep into the block. Then i's
    // ball crosses the face (i's image arrives, with the twin pair) and, before the list is
    // rebuilt, so does the contact point (all in the list's first 20 steps, checked below):
    // the contact-point rule would now pick the twin. It must stay dropped, or the contact is
    // evaluated twice (ContactDetector, "Pairs across a periodic face"). Three small grains far
    // off make j a large sphere and the skin small (0.125).
    core::Comm const world;
    double const cosA = 0.97, sinA = std::sqrt(1.0 - cosA * cosA);
    Vec3 const n(-cosA, sinA, 0.0);         // from i towards j's image
    double const reach = 0.5 + 2.0 - 0.005; // touching by 0.005, i approaching at 0.2
    Vec3 const xi(0.505, 4.0, 4.0);
    Vec3 const xj = xi + reach * n + Vec3(8.0, 0.0, 0.0);
    Vec3 const drift(-1.0, 0.0, 0.0);
    auto scene = [&](std::array<int, 3> blocks) {
        Scene s;
        s.spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
        s.spec.rootBlocks = blocks;
        s.spec.periodic = {true, true, false};
        s.walls = false;
        s.gravity = Vec3::Zero();
        s.steps = 19;
        s.grains = {synctest::grain(1, xi, 0.5, Vec3(drift + 0.2 * n)),
                    synctest::grain(2, xj, 2.0, drift)};
        for (Uid u = 3; u <= 5; ++u)
            s.grains.push_back(
                synctest::grain(u, Vec3(4.0, 1.0, 1.5 * static_cast<double>(u)), 0.5, drift));
        return s;
    };
    SyncConfig const config{SyncMethod::Hybrid, true};
    for (bool keep : {true, false}) {
        SCOPED_TRACE(::testing::Message() << "springs kept " << keep);
        Outcome const a = run(world, scene({1, 1, 1}), config, keep);
        Outcome const b = run(world, scene({2, 2, 1}), config, keep);
        EXPECT_EQ(a.twinsMost, 1);
        EXPECT_EQ(b.twinsMost, 0);
        EXPECT_EQ(a.rebuilds, 1); // one list: i's image and the point crossed during its life
        expectSameState(a, b, 5);
    }
}

} // namespace
