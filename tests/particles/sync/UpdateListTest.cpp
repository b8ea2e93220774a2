// The sync skin (SyncConfig::skin, particles/sync/UpdateList.hpp): shadows decided for balls
// grown by the skin, then copied along a fixed list until a master moved a skin or left its
// block. A random gas drifts through a forest of 2x2x2 blocks, periodic and open:
// every copy Alg. 1 needs exists after every call (the invariants with the skin's tolerance),
// the list carries most calls, masters that cross a block face are handled alone, forces go
// back to the masters along the list, and a storage change ends the list. On several ranks
// (1-8, the same tests) the remote shadows travel along the owners' send lists and every rank
// acts on the same verdict. With SOS a skin is refused on every rank.
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::InputError;

namespace {

constexpr double kSkin = 0.3;

struct Forest {
    Comm world;
    AABB domain{Vec3::Zero(), Vec3(8, 8, 8)};
    domain::BlockForest forest;
    explicit Forest(bool periodic)
        : forest(world, forestSpec(domain.min, domain.max, {2, 2, 2}, allAxes(periodic))) {}
};

struct Calls {
    int alongList = 0;
    int leaversOnly = 0;
    int full = 0;
    void count(SyncStats const& s) {
        alongList += s.alongList ? 1 : 0;
        leaversOnly += s.leaversOnly ? 1 : 0;
        full += !s.alongList && !s.leaversOnly ? 1 : 0;
    }
};

/// A random gas on Forest, set up with a skin: the invariants must hold with the skin's
/// tolerance but not without it (some shadow exists only for the grown ball).
struct SkinnedGas : Forest {
    LocalParticles local;
    ParticleSync sync;
    SkinnedGas(bool periodic, SyncMethod method, std::string const& where)
        : Forest(periodic)
        , local(forest)
        , sync(world, forest, SyncConfig{method, false, kSkin}) {
        addAll(local, world, randomGas(domain, 120, 0.2, 0.6, 1.0, 11));
        sync.requireNnsApplicable(local);
        sync.syncUntilConverged(local);
        auto v = checkSyncInvariants(local, world, true, kSkin);
        EXPECT_TRUE(v.empty()) << where << " after set-up" << joined(v);
        EXPECT_FALSE(checkSyncInvariants(local, world, true, 0.0).empty())
            << where << ": no shadow for the grown balls only";
    }
};

TEST(UpdateList, EveryNeededCopyExistsAndTheListCarriesMostCalls) {
    // Told the drift's largest move (as DemStep tells the integrator's) or not: with the
    // bound the displacements are not compared, only the masters near a face are.
    for (bool bounded : {false, true})
        for (bool periodic : {true, false})
            for (SyncMethod method : {SyncMethod::NextNeighbour, SyncMethod::Hybrid}) {
                std::string const where = methodName(method) + (periodic ? " periodic" : " open") +
                                          " 2x2x2" + (bounded ? ", bound given" : "");
                SkinnedGas g(periodic, method, where);
                LocalParticles& local = g.local;
                ParticleSync& sync = g.sync;
                Calls calls;
                for (int step = 1; step <= 60; ++step) {
                    // At most 0.035 per step: a list lasts several steps.
                    double const moved = drift(local, 0.02);
                    sync.sync(local, bounded ? moved : std::numeric_limits<double>::infinity());
                    calls.count(sync.lastStats());
                    auto const v = checkSyncInvariants(local, g.world, true, kSkin);
                    ASSERT_TRUE(v.empty()) << where << " step " << step << joined(v);
                }
                EXPECT_GT(calls.alongList, 10) << where;
                EXPECT_GT(calls.full, 0) << where << ": never refreshed";
                if (periodic) { // an open domain loses the grains that cross its faces: full calls
                    EXPECT_GT(calls.leaversOnly, 0) << where;
                }
            }
}

TEST(UpdateList, ABoundOnTheMotionIsTrustedAndUnknownMotionIsMeasured) {
    SkinnedGas g(true, SyncMethod::NextNeighbour, "nns periodic");
    LocalParticles& local = g.local;
    ParticleSync& sync = g.sync;
    // One master, deep inside its block, moved by twice the skin: a caller that claims a
    // smaller bound is believed (the contract: the bound must hold) ...
    ParticleStorage* ps = nullptr;
    std::size_t moved = ParticleStorage::kNotFound;
    for (BlockParticles& bp : local.blocks()) {
        AABB const& box = bp.block->aabb;
        for (std::size_t i = 0; i < bp.particles.size() && ps == nullptr; ++i)
            if (bp.particles.flags(i).isMaster() &&
                (bp.particles.position(i) - box.center()).cwiseAbs().maxCoeff() <
                    0.5 * box.minEdge() - 1.0) {
                ps = &bp.particles;
                moved = i;
            }
    }
    // Moved on one rank only (the lowest that has such a master): every rank acts on it.
    int const mover = g.world.allReduce(ps != nullptr ? g.world.rank() : g.world.size(),
                                        regolith::core::ReduceOp::Min);
    ASSERT_LT(mover, g.world.size()) << "no master 1 from its block's faces";
    if (g.world.rank() == mover)
        ps->position(moved) += Vec3(2.0 * kSkin, 0.0, 0.0);
    sync.sync(local, 0.1 * kSkin);
    EXPECT_TRUE(sync.lastStats().alongList);
    // ... and without a bound the positions are compared: a refresh.
    sync.sync(local);
    EXPECT_FALSE(sync.lastStats().alongList);
    EXPECT_FALSE(sync.lastStats().leaversOnly);
    auto const v = checkSyncInvariants(local, g.world, true, kSkin);
    EXPECT_TRUE(v.empty()) << joined(v);
    // Bounds add up: four of a quarter skin each reach the skin, a refresh.
    for (int call = 1; call <= 4; ++call) {
        sync.sync(local, 0.25 * kSkin);
        EXPECT_EQ(sync.lastStats().alongList, call < 4) << "call " << call;
    }
}

TEST(UpdateList, ForcesReachTheMastersAlongTheList) {
    SkinnedGas g(true, SyncMethod::NextNeighbour, "nns periodic");
    LocalParticles& local = g.local;
    ParticleSync& sync = g.sync;
    drift(local, 0.001);
    sync.sync(local);
    ASSERT_TRUE(sync.lastStats().alongList);
    // Every copy gets a force of its own, a multiple of (1, 2, 3) by uid mod 7 for shadows (zero
    // for a seventh of them: nothing to send) and zero for masters: afterwards a master holds
    // the sum over its shadows on every rank (small integers: any order gives the same bits).
    auto share = [](Uid uid) -> Vec3 { return static_cast<double>(uid % 7) * Vec3(1, 2, 3); };
    std::vector<Uid> shadowUids;
    std::uint64_t remote = 0;
    for (BlockParticles& bp : local.blocks()) {
        bp.particles.resetForces();
        for (std::size_t i = 0; i < bp.particles.size(); ++i) {
            if (!bp.particles.flags(i).isShadow())
                continue;
            Uid const uid = bp.particles.uid(i);
            bp.particles.force(i) = share(uid);
            bp.particles.torque(i) = -share(uid);
            shadowUids.push_back(uid);
            remote += bp.particles.owner(i).rank != g.world.rank() ? 1 : 0;
        }
    }
    std::vector<Uid> const all = gatherUids(g.world, shadowUids);
    ASSERT_GT(all.size(), 10u);
    if (g.world.size() > 1) { // the messages along the list are exercised
        EXPECT_GT(g.world.allReduce(remote, regolith::core::ReduceOp::Sum), 0u);
    }
    sync.reduceForces(local, 1);
    for (BlockParticles& bp : local.blocks())
        for (std::size_t i = 0; i < bp.particles.size(); ++i) {
            Uid const uid = bp.particles.uid(i);
            if (bp.particles.flags(i).isShadow()) {
                EXPECT_TRUE(bp.particles.force(i).isZero(0.0)) << "shadow of uid " << uid;
                continue;
            }
            auto const n = static_cast<double>(std::count(all.begin(), all.end(), uid));
            EXPECT_TRUE(sameBits(bp.particles.force(i), Vec3(n * share(uid)))) << "uid " << uid;
            EXPECT_TRUE(sameBits(bp.particles.torque(i), Vec3(Vec3::Zero() - n * share(uid))))
                << "uid " << uid;
        }
}

TEST(UpdateList, AStorageChangeEndsTheList) {
    SkinnedGas g(true, SyncMethod::Hybrid, "hybrid periodic");
    LocalParticles& local = g.local;
    ParticleSync& sync = g.sync;
    sync.sync(local);
    ASSERT_TRUE(sync.lastStats().alongList);
    // A grain added next to a block face (x = 4), by the rank that holds its block: its
    // copies come from the full algorithm, on every rank.
    bool const added = local.addMaster(grain(makeUid(5, 0), Vec3(3.9, 2.0, 2.0), 0.3));
    ASSERT_TRUE(g.world.allReduce(static_cast<int>(added), regolith::core::ReduceOp::Sum) == 1);
    sync.sync(local);
    EXPECT_FALSE(sync.lastStats().alongList);
    EXPECT_GT(g.world.allReduce(sync.lastStats().created, regolith::core::ReduceOp::Sum), 0u);
    auto const v = checkSyncInvariants(local, g.world, true, kSkin);
    EXPECT_TRUE(v.empty()) << joined(v);
}

TEST(UpdateList, ASkinIsRefusedWithSosOrNegative) {
    Forest f(true);
    auto refused = [&](SyncConfig const& c, std::string const& expect) {
        try {
            ParticleSync sync(f.world, f.forest, c);
            ADD_FAILURE() << "accepted: " << expect;
        } catch (InputError const& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
        }
    };
    refused(SyncConfig{SyncMethod::ShadowOwner, false, kSkin}, "sync.skin applies to NNS-class");
    refused(SyncConfig{SyncMethod::Hybrid, false, -1.0}, "sync.skin must be");
}

} // namespace
