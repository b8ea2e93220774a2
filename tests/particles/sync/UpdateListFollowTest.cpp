// UpdateList::followLeavers: after a call that synchronised only the masters that left their
// blocks, a list over traced storages (as the contact detector traces them) catches up with the
// slots that call wrote instead of deciding every copy again. Two twins of a random gas drift
// through a forest of 2x2x2 blocks, periodic, on 1-8 ranks: one traced (it follows), one not (it
// rebuilds). Every call must leave both with the same copies in the same slots, update the same
// number of shadows along the list, and reduce the same forces to the same bits; the traced
// twin must have followed, and kept Alg. 1's invariants.
#include "particles/sync/UpdateList.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <string>

using namespace regolith::particles;
using namespace regolith::particles::synctest;

namespace {

constexpr double kSkin = 0.3;

struct Twin {
    Comm world;
    AABB domain{Vec3::Zero(), Vec3(8, 8, 8)};
    domain::BlockForest forest;
    LocalParticles local;
    ParticleSync sync;
    explicit Twin(SyncMethod method)
        : forest(world, forestSpec(domain.min, domain.max, {2, 2, 2}, allAxes(true)))
        , local(forest)
        , sync(world, forest, SyncConfig{method, false, kSkin}) {
        addAll(local, world, randomGas(domain, 120, 0.2, 0.6, 1.0, 11));
        sync.syncUntilConverged(local);
    }
};

/// Where the twins differ: slot by slot, uid, image, class and position bits.
std::string difference(LocalParticles const& a, LocalParticles const& b) {
    auto const ba = a.blocks();
    auto const bb = b.blocks();
    for (std::size_t k = 0; k < ba.size(); ++k) {
        ParticleStorage const& x = ba[k].particles;
        ParticleStorage const& y = bb[k].particles;
        if (x.size() != y.size())
            return "block " + std::to_string(k) + ": sizes differ";
        for (std::size_t i = 0; i < x.size(); ++i)
            if (x.uid(i) != y.uid(i) || !sameImage(x.image(i), y.image(i)) ||
                x.flags(i).isShadow() != y.flags(i).isShadow() ||
                !sameBits(x.position(i), y.position(i)) || !sameBits(x.force(i), y.force(i)))
                return "block " + std::to_string(k) + " slot " + std::to_string(i);
    }
    return {};
}

/// Forces on every shadow that depend on its uid and slot, so that a reduction in another
/// order or onto another master shows in the masters' bits.
void shadowForces(LocalParticles& local) {
    for (BlockParticles& bp : local.blocks()) {
        ParticleStorage& ps = bp.particles;
        ps.resetForces();
        for (std::size_t i = 0; i < ps.size(); ++i)
            if (ps.flags(i).isShadow())
                ps.force(i) = Vec3(0.1 + 1e-3 * static_cast<double>(ps.uid(i) % 97),
                                   1.0 / static_cast<double>(i + 3), 0.3);
    }
}

} // namespace

TEST(UpdateListFollow, TracedStoragesFollowTheLeaversAsARebuildListsThem) {
    for (SyncMethod method : {SyncMethod::NextNeighbour, SyncMethod::Hybrid}) {
        std::string const where = methodName(method) + " periodic 2x2x2";
        Twin traced(method), rebuilt(method);
        ASSERT_EQ(difference(traced.local, rebuilt.local), "") << where << " after set-up";
        int followed = 0, leavers = 0;
        for (int step = 1; step <= 80; ++step) {
            // Traced as the contact detector traces: restarted now and then, the journal
            // emptied after most calls (a detector follows it every step).
            for (BlockParticles& bp : traced.local.blocks())
                if (step % 25 == 1)
                    bp.particles.startTracing();
                else if (step % 3 != 0)
                    bp.particles.clearTraceJournal();
            double const moved = drift(traced.local, 0.02);
            ASSERT_TRUE(sameBits(Vec3(moved, 0, 0), Vec3(drift(rebuilt.local, 0.02), 0, 0)));
            traced.sync.sync(traced.local, moved);
            rebuilt.sync.sync(rebuilt.local, moved);
            SyncStats const& t = traced.sync.lastStats();
            SyncStats const& r = rebuilt.sync.lastStats();
            ASSERT_EQ(t.alongList, r.alongList) << where << " step " << step;
            ASSERT_EQ(t.leaversOnly, r.leaversOnly) << where << " step " << step;
            EXPECT_EQ(t.updated, r.updated) << where << " step " << step;
            EXPECT_FALSE(r.listFollowed) << where << " step " << step << ": untraced";
            followed += t.listFollowed ? 1 : 0;
            leavers += t.leaversOnly ? 1 : 0;
            ASSERT_EQ(difference(traced.local, rebuilt.local), "") << where << " step " << step;
            auto const v = checkSyncInvariants(traced.local, traced.world, true, kSkin);
            ASSERT_TRUE(v.empty()) << where << " step " << step << joined(v);
            shadowForces(traced.local);
            shadowForces(rebuilt.local);
            traced.sync.reduceForces(traced.local, 1);
            rebuilt.sync.reduceForces(rebuilt.local, 1);
            EXPECT_EQ(traced.sync.lastReductionAlongList(), rebuilt.sync.lastReductionAlongList())
                << where << " step " << step;
            ASSERT_EQ(difference(traced.local, rebuilt.local), "")
                << where << " step " << step << ", reduced";
        }
        EXPECT_GT(leavers, 3) << where;
        EXPECT_EQ(traced.world.allReduce(followed, regolith::core::ReduceOp::Min), leavers)
            << where << ": every call for the leavers followed, on every rank";
    }
}
