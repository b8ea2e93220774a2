// Pairs across a periodic face, with springs kept beside the lists: a region that spans the
// domain along a periodic axis holds every image instance of such a pair, and the
// contact-point rule must pick exactly one each step, on every layout, with the same bits as
// layouts that tile the domain and as the runs that keep every spring in the grains' histories.
#include "tests/particles/simulation/KeptSpringsHarness.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <gtest/gtest.h>

using namespace regolith;
using namespace regolith::particles;
using namespace regolith::particles::kept_springs;

namespace {

TEST(KeptSprings, PairsAcrossPeriodicFacesChangeNoBitOnAnyLayout) {
    // A block spanning the periodic domain along an axis (the whole domain, or one of three
    // strips along y, each spanning x) holds every image instance of a pair across such a face;
    // blocks that tile the domain along every axis hold one or two. In reproducible mode the
    // layouts must end with the same bits: a face contact doubled or missed shows (on several
    // ranks, or on one with a block per strip). A drift carries the grains across the x and y
    // faces while they touch: grains wrap, and images arrive as grains start to cross a face
    // (drifting down x and y: the lower uid of a face pair, near the lower face, moves towards
    // it).
    core::Comm const world;
    for (double r : {kRadius, 0.6}) {
        for (double drift : {2.0, -2.0}) {
            Outcome tiledInHistories;
            for (bool keep : {false, true}) {
                SCOPED_TRACE(::testing::Message()
                             << "springs kept " << keep << ", radius " << r << ", drift " << drift);
                Scene one = packing({1, 1, 1}, 0.3, r);
                Scene strips = packing({1, 3, 1}, 0.3, r);
                Scene tiled = packing({3, 2, 1}, 0.3, r);
                for (Scene* s : {&one, &strips, &tiled})
                    for (ParticleInit& g : s->grains)
                        g.velocity += Vec3(drift, 0.65 * drift, 0.0);
                SyncConfig const config{SyncMethod::Hybrid, true};
                Outcome const a = run(world, one, config, keep);
                Outcome const s = run(world, strips, config, keep);
                Outcome const b = run(world, tiled, config, keep);
                expectSameState(a, b, one.grains.size());
                expectSameState(s, b, one.grains.size());
                if (!keep) {
                    tiledInHistories = b;
                    continue;
                }
                EXPECT_GT(a.keptMost, 0); // the springs beside the lists were exercised
                expectSameState(b, tiledInHistories, one.grains.size());
            }
        }
    }
}

TEST(KeptSprings, AContactPointCrossingAPeriodicFaceIsEvaluatedOnce) {
    // A small grain i (lower uid) touches a large grain j's image across the face x = 0 at a
    // slant, the two drifting towards -x together. Then i's ball crosses the face (i's image
    // arrives, with a second instance of the pair) and, before the list is rebuilt, so does the
    // contact point (all in the list's first 20 steps: one list, checked below): the rule moves
    // from the one instance to the other, and the contact must be evaluated once, as on blocks that
    // tile the domain. Three small grains far off make j a large sphere and the skin small (0.125).
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
    Outcome const a = run(world, scene({1, 1, 1}), config, true);
    Outcome const b = run(world, scene({2, 2, 1}), config, true);
    EXPECT_EQ(a.rebuilds, 1); // one list: i's image and the point crossed during its life
    expectSameState(a, b, 5);
}

} // namespace
