// Periodic axes with one or two blocks: along an axis every block spans (one block) the
// particles wrap and keep no image (wrappedAxes); with two blocks each is its neighbour's on
// both sides. Copies appear at their periodic images in the right blocks, and the invariants
// hold while a gas moves -- where a common reference implementation demands three blocks per
// periodic axis. (A block that spans an axis that others do not holds its own images:
// UpdateListTest's refined row.)
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;

namespace {

/// x: one block of 6, y: two blocks of 4, z: three blocks of 3; all periodic.
domain::ForestSpec smallAxes() {
    return forestSpec(Vec3::Zero(), Vec3(6, 8, 9), {1, 2, 3}, allAxes(true));
}

} // namespace

TEST(PeriodicSmallAxes, CopiesSitAtTheirImages) {
    Comm world;
    domain::BlockForest const forest(world, smallAxes());
    for (SyncMethod m : {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        ParticleSync sync(world, forest, SyncConfig{m, false});
        // A grain in the corner of block (0, 0, 0): its images through y (the other y block)
        // and z (the last z block) reach back into the domain; across x it wraps.
        Uid const uid = makeUid(0, 3);
        Vec3 const x(0.2, 0.25, 0.15);
        double const r = 0.5;
        addAll(local, world, {grain(uid, x, r)});
        sync.requireNnsApplicable(local);
        sync.syncUntilConverged(local);
        std::string const where = methodName(m);
        std::uint64_t const copies = expectPresence(local, uid, x, r, where);
        // Images (0, dy, dz) with dy in {0, 1}, dz in {0, 1} (x wraps: every block spans
        // it): 4 copies in 4 blocks, the master among them.
        EXPECT_EQ(world.allReduce(copies, regolith::core::ReduceOp::Sum), 4U) << where;
        if (domain::Block const* b = forest.localBlockContaining(x)) {
            ParticleStorage const& ps = local.find(b->id.raw())->particles;
            EXPECT_FALSE(ps.contains(uid, CopyImage{1, 0, 0})) << where << ": self image";
            std::size_t const mi = ps.find(uid);
            ASSERT_NE(mi, ParticleStorage::kNotFound);
            EXPECT_EQ(ps.shadowHolders(mi).size(), 3U) << where;
        }
        auto const v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << where << joined(v);
    }
}

TEST(PeriodicSmallAxes, GasKeepsTheInvariants) {
    Comm world;
    domain::BlockForest const forest(world, smallAxes());
    for (SyncMethod m : {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        ParticleSync sync(world, forest, SyncConfig{m, false});
        auto const gas = randomGas(forest.domain(), 80, 0.2, 0.9, 1.5, 21);
        addAll(local, world, gas);
        sync.syncUntilConverged(local);
        for (int step = 1; step <= 30; ++step) {
            drift(local, 0.1);
            sync.sync(local);
            std::string const where = methodName(m) + " step " + std::to_string(step);
            EXPECT_EQ(globalMasters(local, world), gas.size()) << where;
            auto const v = checkSyncInvariants(local, world, true);
            EXPECT_TRUE(v.empty()) << where << joined(v);
        }
    }
}

TEST(PeriodicSmallAxes, OneBlockOnEveryAxis) {
    // The whole domain is one block, one subdomain: its axes wrap, so the grain holds no image
    // and wraps in place when it crosses the corner.
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3(5, 5, 5), {1, 1, 1}, allAxes(true)));
    for (SyncMethod m : {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        ParticleSync sync(world, forest, SyncConfig{m, false});
        Uid const uid = makeUid(0, 1);
        addAll(local, world, {grain(uid, Vec3(0.2, 4.9, 0.3), 0.6)});
        sync.syncUntilConverged(local);
        std::uint64_t const copies =
            expectPresence(local, uid, Vec3(0.2, 4.9, 0.3), 0.6, methodName(m));
        EXPECT_EQ(world.allReduce(copies, regolith::core::ReduceOp::Sum), 1U) << methodName(m);
        // Move it across the corner of the domain and back.
        for (int step = 1; step <= 8; ++step) {
            if (auto const [bp, i] = findMaster(local, uid); bp != nullptr)
                bp->particles.position(i) += Vec3(-0.1, 0.1, -0.1) * (step <= 4 ? 1.0 : -1.0);
            sync.sync(local);
            auto const v = checkSyncInvariants(local, world, true);
            EXPECT_TRUE(v.empty()) << methodName(m) << " step " << step << joined(v);
        }
        GrainView const g = viewGrain(local, world, uid);
        EXPECT_LT((g.position - Vec3(0.2, 4.9, 0.3)).norm(), 1e-12) << methodName(m);
    }
}
