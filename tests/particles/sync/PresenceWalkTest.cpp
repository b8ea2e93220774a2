// Presence walk: one sphere is moved in small steps through a 3x3x3 forest of
// edge-10 blocks, across faces, edges and corners (and, periodic, across the domain's faces,
// edges and its corner); after every synchronisation every block holds a copy at image k iff
// the sphere's image reaches it, and the master iff it contains the centre. Meant for 27 ranks
// (one block each) and run at 1, 2, 4 and 8 too (several blocks per rank).
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <cmath>
#include <sstream>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::synctest;

namespace {

struct WalkCase {
    SyncMethod method;
    double radius;
    bool periodic;
    double step; ///< path length per move
};

std::string name(WalkCase const& c) {
    std::ostringstream s;
    s << methodName(c.method) << " r=" << c.radius << (c.periodic ? " periodic" : " open");
    return s.str();
}

/// Waypoints, unwrapped. Offsets keep every stop off the distance-r shells of faces and edges.
/// Leg 1 crosses a face, leg 2 an edge (x = 20, y = 10 within one move), leg 3 a corner
/// (20, 20, 10), leg 4 the corner (10, 20, 20); periodic: leg 5 the corner (0, 20, 30) on
/// two periodic faces, leg 6 the domain corner (0, 30, 30) == (0, 0, 0) on all three.
std::vector<Vec3> path(bool periodic) {
    Vec3 const o(0.013, 0.027, -0.019);
    std::vector<Vec3> w{Vec3(5, 5, 5) + o, Vec3(15, 5, 5) + o, Vec3(25, 15, 5) + o,
                        Vec3(15, 25, 15) + o, Vec3(5, 15, 25) + o};
    if (periodic) {
        w.push_back(Vec3(-5, 25, 35) + o);
        w.push_back(Vec3(5, 35, 25) + o);
    }
    return w;
}

/// `target` moved by whole periods to the image nearest to `current`, so the master moves
/// by one small step in its own frame.
Vec3 nearestImage(Vec3 target, Vec3 const& current, Vec3 const& period) {
    for (int a = 0; a < 3; ++a)
        if (period[a] > 0)
            target[a] += period[a] * std::round((current[a] - target[a]) / period[a]);
    return target;
}

void walk(WalkCase const& c) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(30), {3, 3, 3}, allAxes(c.periodic)));
    Vec3 const period = periodOf(forest);
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{c.method, false});
    Uid const uid = makeUid(0, 42);
    std::vector<Vec3> const w = path(c.periodic);
    EXPECT_EQ(addAll(local, world, {grain(uid, w.front(), c.radius)}), 1U) << name(c);
    sync.requireNnsApplicable(local);
    sync.syncUntilConverged(local);

    auto check = [&](std::string const& where, Vec3 const& intended) {
        GrainView const g = viewGrain(local, world, uid);
        EXPECT_EQ(g.count, 1) << where;
        EXPECT_LT((g.position - forest.wrap(intended)).norm(), 1e-9)
            << where << ": master at (" << g.position.transpose() << ")";
        std::uint64_t const copies = expectPresence(local, uid, g.position, c.radius, where);
        EXPECT_GT(world.allReduce(copies, regolith::core::ReduceOp::Sum), 0U) << where;
    };
    check(name(c) + " start", w.front());

    int moves = 0;
    for (std::size_t leg = 0; leg + 1 < w.size(); ++leg) {
        auto const n = static_cast<int>(std::ceil((w[leg + 1] - w[leg]).norm() / c.step));
        for (int s = 1; s <= n; ++s) {
            Vec3 const target = w[leg] + (w[leg + 1] - w[leg]) * (static_cast<double>(s) / n);
            if (auto const [bp, i] = findMaster(local, uid); bp != nullptr)
                bp->particles.position(i) = nearestImage(target, bp->particles.position(i), period);
            sync.sync(local);
            ++moves;
            check(name(c) + " leg " + std::to_string(leg) + " move " + std::to_string(s), target);
            if (moves % 25 == 0) {
                auto const v = checkSyncInvariants(local, world, true);
                EXPECT_TRUE(v.empty()) << name(c) << " move " << moves << joined(v);
            }
        }
    }
    auto const v = checkSyncInvariants(local, world, true);
    EXPECT_TRUE(v.empty()) << name(c) << " at the end" << joined(v);
}

} // namespace

TEST(PresenceWalk, SmallSphereNns) {
    for (bool periodic : {false, true})
        walk({SyncMethod::NextNeighbour, 1.0, periodic, 0.75});
}

TEST(PresenceWalk, SmallSphereSos) {
    for (bool periodic : {false, true})
        walk({SyncMethod::ShadowOwner, 1.0, periodic, 0.75});
}

TEST(PresenceWalk, SmallSphereHybrid) {
    for (bool periodic : {false, true})
        walk({SyncMethod::Hybrid, 1.0, periodic, 0.75});
}

// r = 20 on edge-10 blocks: the sphere reaches two block layers and, periodic, several images
// of one block (the domain is 30 wide). One synchronisation per move after set-up.
TEST(PresenceWalk, LargeSphereSos) {
    for (bool periodic : {false, true})
        walk({SyncMethod::ShadowOwner, 20.0, periodic, 1.25});
}

TEST(PresenceWalk, LargeSphereHybrid) {
    for (bool periodic : {false, true})
        walk({SyncMethod::Hybrid, 20.0, periodic, 1.25});
}
