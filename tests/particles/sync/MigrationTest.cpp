// Migration: masters moved across block faces, the central corner of the forest (to the
// diagonally opposite block) and periodic faces and corners end in the block containing their
// centre, on whatever rank owns it, and take their force, torque, velocity and contact history
// with them (forces travel with migrating masters between postForce and the next preForce).
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::ReduceOp;

namespace {

struct Mover {
    Uid uid;
    Vec3 from;
    Vec3 to; ///< unwrapped: beyond the domain on a periodic axis
};

std::vector<Mover> movers(bool periodic) {
    std::vector<Mover> m;
    std::uint64_t n = 0;
    // Through the central corner (10, 10, 10): from each block to the opposite one.
    for (int s = 0; s < 8; ++s) {
        Vec3 const sign((s & 1) != 0 ? 1 : -1, (s & 2) != 0 ? 1 : -1, (s & 4) != 0 ? 1 : -1);
        m.push_back({makeUid(0, n++), Vec3::Constant(10) + 0.2 * sign + Vec3(0.01, 0.02, 0.03),
                     Vec3::Constant(10) - 0.3 * sign + Vec3(0.01, 0.02, 0.03)});
    }
    // Across the three faces of block (0, 0, 0).
    m.push_back({makeUid(0, n++), Vec3(9.8, 5.3, 5.1), Vec3(10.3, 5.3, 5.1)});
    m.push_back({makeUid(0, n++), Vec3(4.7, 9.9, 5.6), Vec3(4.7, 10.2, 5.6)});
    m.push_back({makeUid(0, n++), Vec3(5.5, 4.4, 9.7), Vec3(5.5, 4.4, 10.1)});
    if (periodic) {
        m.push_back({makeUid(0, n++), Vec3(19.8, 15.2, 15.4), Vec3(20.3, 15.2, 15.4)});
        m.push_back({makeUid(0, n++), Vec3(0.2, 3.1, 12.4), Vec3(-0.25, 3.1, 12.4)});
        m.push_back({makeUid(0, n++), Vec3(19.9, 19.8, 19.7), Vec3(20.2, 20.1, 20.05)});
        m.push_back({makeUid(0, n++), Vec3(0.1, 19.9, 0.3), Vec3(-0.2, 20.3, -0.1)});
    }
    return m;
}

/// The rank holding the master of `uid` (-1 if none; the largest if several). COLLECTIVE.
int masterRank(LocalParticles& local, Comm const& comm, Uid uid) {
    return comm.allReduce(findMaster(local, uid).first != nullptr ? comm.rank() : -1,
                          ReduceOp::Max);
}

Vec3 forceOf(Uid uid) {
    double const u = static_cast<double>(uidCounter(uid)) + 1.0;
    return Vec3(1.0 / 3.0, -2.0, 3.0) * u;
}
Vec3 torqueOf(Uid uid) {
    double const u = static_cast<double>(uidCounter(uid)) + 1.0;
    return Vec3(-4.0, 5.0 / 7.0, -6.0) * u;
}
HistoryEntry historyOf(Uid uid) {
    double const u = static_cast<double>(uidCounter(uid)) + 1.0;
    return HistoryEntry{makeUid(9, uidCounter(uid)), Vec3(0.1, 0.2, 0.3) * u, 17};
}

/// Sets the dynamic state of every local master and moves it to `target(m)`.
template <class Target>
void moveAll(LocalParticles& local, std::vector<Mover> const& ms, Target&& target) {
    for (Mover const& m : ms) {
        auto const [bp, i] = findMaster(local, m.uid);
        if (bp == nullptr)
            continue;
        ParticleStorage& ps = bp->particles;
        ps.force(i) = forceOf(m.uid);
        ps.torque(i) = torqueOf(m.uid);
        ps.velocity(i) = Vec3(0.5, -0.25, 0.125);
        ps.history(i).clear();
        ps.history(i).set(historyOf(m.uid));
        ps.position(i) = target(m);
    }
}

void expectArrived(LocalParticles& local, Comm const& comm, Mover const& m, Vec3 const& to,
                   std::string const& where) {
    GrainView const g = viewGrain(local, comm, m.uid);
    EXPECT_EQ(g.count, 1) << where << " uid " << m.uid;
    auto const [bp, i] = findMaster(local, m.uid);
    if (bp == nullptr)
        return;
    ParticleStorage const& ps = bp->particles;
    Vec3 const expected = local.forest().wrap(to);
    EXPECT_LT((ps.position(i) - expected).norm(), 1e-12) << where << " uid " << m.uid;
    EXPECT_TRUE(bp->block->aabb.contains(ps.position(i))) << where << " uid " << m.uid;
    EXPECT_TRUE(sameBits(ps.force(i), forceOf(m.uid))) << where << " force of uid " << m.uid;
    EXPECT_TRUE(sameBits(ps.torque(i), torqueOf(m.uid))) << where << " torque of uid " << m.uid;
    EXPECT_TRUE(sameBits(ps.velocity(i), Vec3(0.5, -0.25, 0.125))) << where;
    HistoryEntry const h = historyOf(m.uid);
    HistoryEntry const* e = ps.history(i).find(h.partner);
    ASSERT_NE(e, nullptr) << where << ": history of uid " << m.uid << " lost";
    EXPECT_TRUE(sameBits(e->spring, h.spring)) << where;
    EXPECT_EQ(e->stamp, h.stamp) << where;
    EXPECT_EQ(ps.history(i).size(), 1U) << where;
}

void migrate(SyncMethod method, bool periodic) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(20), {2, 2, 2}, allAxes(periodic)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{method, false});
    std::vector<Mover> const ms = movers(periodic);
    std::vector<ParticleInit> grains;
    for (Mover const& m : ms)
        grains.push_back(grain(m.uid, m.from, 0.6));
    EXPECT_EQ(addAll(local, world, grains), ms.size());
    sync.syncUntilConverged(local);
    std::string const label = methodName(method) + (periodic ? " periodic" : " open");

    std::vector<int> before;
    for (Mover const& m : ms)
        before.push_back(masterRank(local, world, m.uid));
    // There and back: each way crosses the same boundaries.
    for (int way = 0; way < 2; ++way) {
        std::string const where = label + (way == 0 ? " there" : " back");
        moveAll(local, ms, [&](Mover const& m) {
            if (way == 0)
                return m.to;
            // Back to `from`, seen from the frame the master now lives in.
            Vec3 back = m.from;
            Vec3 const shift = local.forest().wrap(m.to) - m.to;
            return Vec3(back + shift);
        });
        sync.sync(local);
        int crossRank = 0;
        for (std::size_t k = 0; k < ms.size(); ++k) {
            expectArrived(local, world, ms[k], way == 0 ? ms[k].to : ms[k].from, where);
            int const now = masterRank(local, world, ms[k].uid);
            crossRank += now != before[k] ? 1 : 0;
            before[k] = now;
        }
        if (world.size() > 1) {
            EXPECT_GT(crossRank, 0) << where << ": some master should change rank";
        }
        auto const v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << where << joined(v);
    }
}

} // namespace

TEST(Migration, Nns) {
    migrate(SyncMethod::NextNeighbour, false);
    migrate(SyncMethod::NextNeighbour, true);
}

TEST(Migration, Sos) {
    migrate(SyncMethod::ShadowOwner, false);
    migrate(SyncMethod::ShadowOwner, true);
}

TEST(Migration, Hybrid) {
    migrate(SyncMethod::Hybrid, false);
    migrate(SyncMethod::Hybrid, true);
}

// A shadow's force is not a master's: after reduceForces shadows are zero and the master
// holds the sum; a shadow's history entries of this pass reach the master.
TEST(Migration, ReducedForceAndHistoryArriveAtTheMaster) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(20), {2, 2, 2}, allAxes(true)));
    for (SyncMethod method :
         {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        ParticleSync sync(world, forest, SyncConfig{method, false});
        Uid const uid = makeUid(0, 5);
        addAll(local, world, {grain(uid, Vec3(19.7, 9.8, 0.2), 0.7)}); // 8 copies
        sync.syncUntilConverged(local);
        std::uint64_t shadows = 0;
        Uid const partner = makeUid(9, 1);
        for (BlockParticles& bp : local.blocks()) {
            bp.particles.resetForces();
            for (std::size_t i = 0; i < bp.particles.size(); ++i) {
                bp.particles.force(i) = Vec3(1.0, 0.0, -0.5); // every copy contributes
                bp.particles.torque(i) = Vec3(0.0, 0.25, 0.0);
                if (bp.particles.flags(i).isShadow()) {
                    ++shadows;
                    bp.particles.history(i).touch(partner, 3).spring = Vec3(0.5, 0.0, 0.0);
                }
            }
        }
        std::uint64_t const total = world.allReduce(shadows, ReduceOp::Sum);
        EXPECT_EQ(total, 7U) << methodName(method);
        sync.reduceForces(local, 3);
        for (BlockParticles const& bp : local.blocks())
            for (std::size_t i = 0; i < bp.particles.size(); ++i) {
                ParticleStorage const& ps = bp.particles;
                if (ps.flags(i).isShadow()) {
                    EXPECT_TRUE(ps.force(i).isZero(0.0)) << methodName(method);
                    continue;
                }
                double const n = static_cast<double>(total) + 1.0;
                EXPECT_EQ(ps.force(i), Vec3(n, 0.0, -0.5 * n)) << methodName(method);
                EXPECT_EQ(ps.torque(i), Vec3(0.0, 0.25 * n, 0.0)) << methodName(method);
                HistoryEntry const* e = ps.history(i).find(partner);
                ASSERT_NE(e, nullptr) << methodName(method);
                EXPECT_EQ(e->spring, Vec3(0.5, 0.0, 0.0));
                EXPECT_EQ(e->stamp, 3U);
            }
    }
}

// A master that crosses a periodic face by less than an ulp of the period: its new canonical
// position x + period rounds to the domain's upper face unless it is kept inside (as
// ForestGeometry::wrap clamps); it must land inside the block that holds it.
TEST(Migration, TinyCrossingOfAPeriodicFaceLandsInsideTheDomain) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(5), {1, 2, 2}, allAxes(true)));
    for (SyncMethod method :
         {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        ParticleSync sync(world, forest, SyncConfig{method, false});
        Uid const uid = makeUid(0, 1);
        addAll(local, world, {grain(uid, Vec3(0.2, 1.0, 0.3), 0.4)});
        sync.syncUntilConverged(local);
        if (auto const [bp, i] = findMaster(local, uid); bp != nullptr)
            bp->particles.position(i)[2] = -2.7755575615628914e-17; // 0.3 - 3 * 0.1
        sync.sync(local);
        GrainView const g = viewGrain(local, world, uid);
        EXPECT_EQ(g.count, 1) << methodName(method);
        EXPECT_LT(g.position[2], 5.0) << methodName(method);
        auto const v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << methodName(method) << joined(v);
    }
}
