// The sync skin (SyncConfig::skin, particles/sync/UpdateList.hpp): shadows decided for balls
// grown by the skin, then copied along a fixed list until a master moved a skin or left its
// block. A random gas drifts through a forest of 2x2x2 blocks, periodic and open:
// every copy Alg. 1 needs exists after every call (the invariants with the skin's tolerance),
// the list carries most calls, masters that cross a block face are handled alone, forces go
// back to the masters along the list with the springs the shadows touched, a storage change on
// one rank sends every rank the keyed way, a storage change ends the list, an SOS-class grain
// (hybrid) leaves it idle while it exists, and an idle call leaves every shadow in its master's
// storage with the master's history. On several ranks
// (1-8, the same tests) the remote shadows travel along the owners' send lists and every rank
// acts on the same verdict. With SOS a skin is refused on every rank.
#include "particles/sync/UpdateList.hpp"

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
    /// One call after a small drift, carried along the list.
    void callAlongTheList() {
        drift(local, 0.001);
        sync.sync(local);
        EXPECT_TRUE(sync.lastStats().alongList);
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

/// Shares for every shadow of `local` (on Forest) before a force reduction of pass 1, and the
/// check that they reached the masters: a force and torque of its own, a multiple of (1, 2, 3)
/// by uid mod 7 (zero for a seventh of the shadows: nothing to send unless they touched a
/// spring), and for the shadows whose uid is a multiple of 3 a spring touched in pass 1 keyed
/// by that shadow's block and image (each must reach the master: a master with several
/// shadows gets one from each) beside one left from pass 0 (it must not). Small integers: any
/// order of the sums gives the same bits.
struct ShadowShares {
    Comm const& world;
    std::vector<Uid> all;     ///< every rank's shadows' uids
    std::vector<Uid> springs; ///< every rank's touched springs' partners
    static Vec3 share(Uid uid) { return static_cast<double>(uid % 7) * Vec3(1, 2, 3); }
    /// The partner of the spring the shadow of `uid` in `box` at image `k` touched: the grain's
    /// counter times 256 plus the block (of Forest's 2 x 2 x 2) and the image.
    static Uid touched(Uid uid, AABB const& box, CopyImage const& k) {
        std::uint64_t code = 0;
        for (int a = 0; a < 3; ++a)
            code = 2 * code + (box.min[a] > 1.0 ? 1 : 0);
        for (std::size_t a = 0; a < 3; ++a)
            code = 3 * code + static_cast<std::uint64_t>(k[a] + 1);
        return makeUid(9, uidCounter(uid) * 256 + code);
    }
    static Uid stale(Uid uid) { return makeUid(10, uidCounter(uid)); }

    ShadowShares(Comm const& w, LocalParticles& local)
        : world(w) {
        std::vector<Uid> shadowUids, partners;
        std::uint64_t remote = 0;
        for (BlockParticles& bp : local.blocks()) {
            ParticleStorage& ps = bp.particles;
            ps.resetForces();
            for (std::size_t i = 0; i < ps.size(); ++i) {
                if (!ps.flags(i).isShadow())
                    continue;
                Uid const uid = ps.uid(i);
                ps.force(i) = share(uid);
                ps.torque(i) = -share(uid);
                if (uid % 3 == 0) {
                    Uid const partner = touched(uid, bp.block->aabb, ps.image(i));
                    ps.history(i).set(HistoryEntry{partner, share(uid), 1});
                    ps.history(i).set(HistoryEntry{stale(uid), share(uid), 0});
                    partners.push_back(partner);
                }
                shadowUids.push_back(uid);
                remote += ps.owner(i).rank != world.rank() ? 1 : 0;
            }
        }
        all = gatherUids(world, shadowUids);
        springs = gatherUids(world, partners);
        EXPECT_GT(all.size(), 10u);
        if (world.size() > 1) { // the messages to other ranks are exercised
            EXPECT_GT(world.allReduce(remote, regolith::core::ReduceOp::Sum), 0u);
        }
    }

    void expectReduced(LocalParticles& local, std::string const& where) const {
        for (BlockParticles& bp : local.blocks()) {
            ParticleStorage& ps = bp.particles;
            for (std::size_t i = 0; i < ps.size(); ++i) {
                Uid const uid = ps.uid(i);
                if (ps.flags(i).isShadow()) {
                    EXPECT_TRUE(ps.force(i).isZero(0.0)) << where << ": shadow of uid " << uid;
                    continue;
                }
                auto const n = static_cast<double>(std::count(all.begin(), all.end(), uid));
                EXPECT_TRUE(sameBits(ps.force(i), Vec3(n * share(uid))))
                    << where << ": uid " << uid;
                EXPECT_TRUE(sameBits(ps.torque(i), Vec3(Vec3::Zero() - n * share(uid))))
                    << where << ": uid " << uid;
                // Exactly the springs its shadows touched, none left from pass 0.
                std::vector<Uid> expected, found;
                for (Uid p : springs)
                    if (uidRank(uid) == 0 && uidCounter(p) / 256 == uidCounter(uid))
                        expected.push_back(p);
                for (HistoryEntry const& e : ps.history(i)) {
                    EXPECT_NE(e.partner, stale(uid)) << where << ": uid " << uid;
                    if (uidRank(e.partner) == 9) {
                        found.push_back(e.partner);
                        EXPECT_TRUE(sameBits(e.spring, share(uid))) << where << ": uid " << uid;
                        EXPECT_EQ(e.stamp, 1u) << where << ": uid " << uid;
                    }
                }
                EXPECT_EQ(found, expected) << where << ": the springs of uid " << uid;
            }
        }
    }
};

TEST(UpdateList, ForcesAndSpringsReachTheMastersAlongTheList) {
    SkinnedGas g(true, SyncMethod::NextNeighbour, "nns periodic");
    g.callAlongTheList();
    ShadowShares const shares(g.world, g.local);
    g.sync.reduceForces(g.local, 1);
    EXPECT_TRUE(g.sync.lastReductionAlongList());
    shares.expectReduced(g.local, "along the list");
}

TEST(UpdateList, AStorageChangeOnOneRankSendsEveryRankTheKeyedWay) {
    SkinnedGas g(true, SyncMethod::Hybrid, "hybrid periodic");
    g.callAlongTheList();
    ShadowShares const shares(g.world, g.local);
    // Between the sync and the reduction one rank's storage changes (a grain deep inside a
    // block, no shadows): that rank cannot use the list, so no rank may (its peers would wait
    // for shares by list position that never come, or read keyed ones as such).
    bool const added = g.local.addMaster(grain(makeUid(5, 1), Vec3(2.0, 2.0, 2.0), 0.2));
    ASSERT_EQ(g.world.allReduce(static_cast<int>(added), regolith::core::ReduceOp::Sum), 1);
    g.sync.reduceForces(g.local, 1);
    EXPECT_FALSE(g.sync.lastReductionAlongList());
    shares.expectReduced(g.local, "keyed, after a change on one rank");
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

TEST(UpdateList, AnSosClassGrainIdlesTheListUntilItIsGone) {
    // Hybrid on an open forest of 4 x 4 x 4 blocks of edge 2: a gas at rest and, in a corner,
    // one grain wider than a block (SOS class), whose copies reach 8 of the 64 blocks: on
    // several ranks some rank holds none, acts on the others' verdict and must idle too.
    Comm world;
    AABB const domain{Vec3::Zero(), Vec3(8, 8, 8)};
    domain::BlockForest forest(world,
                               forestSpec(domain.min, domain.max, {4, 4, 4}, allAxes(false)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::Hybrid, false, kSkin});
    addAll(local, world, randomGas(domain, 120, 0.2, 0.6, 0.0, 11));
    Uid const big = makeUid(1, 0);
    addAll(local, world, {grain(big, Vec3(1.0, 1.0, 1.0), 2.2)});
    // The first call's refresh meets the SOS-class copies; the calls after it are idle: the
    // full algorithm without growth (exactly Alg. 1/2's copies), no refresh.
    int idle = sync.syncUntilConverged(local) - 1;
    while (idle < UpdateList::kIdleCalls) {
        sync.sync(local);
        ASSERT_TRUE(sync.lastStats().skinIdle) << "idle call " << idle + 1;
        auto const v = checkSyncInvariants(local, world, true, 0.0);
        EXPECT_TRUE(v.empty()) << "idle call " << idle + 1 << joined(v);
        ++idle;
    }
    if (world.size() > 1) { // some rank holds no copy of the grain
        bool const holds = std::ranges::any_of(local.blocks(), [&](BlockParticles const& bp) {
            return bp.particles.find(big) != ParticleStorage::kNotFound; // open: image 0
        });
        EXPECT_LT(world.allReduce(static_cast<int>(holds), regolith::core::ReduceOp::Sum),
                  world.size());
    }
    sync.sync(local); // a refresh tried again, with growth: it meets the grain again
    EXPECT_FALSE(sync.lastStats().skinIdle);
    EXPECT_FALSE(sync.lastStats().alongList);
    EXPECT_TRUE(checkSyncInvariants(local, world, true, kSkin).empty());
    // Idle again, twice as long: the grain is still there.
    for (int call = 1; call <= 2 * UpdateList::kIdleCalls; ++call) {
        sync.sync(local);
        ASSERT_TRUE(sync.lastStats().skinIdle) << "second idle stretch, call " << call;
    }
    sync.sync(local);
    EXPECT_FALSE(sync.lastStats().skinIdle);
    // The large grain leaves the domain: the list carries calls again once the idle ones (4 x
    // kIdleCalls now) ran.
    if (auto [bp, i] = findMaster(local, big); bp != nullptr)
        bp->particles.position(i) = Vec3(-4.0, 1.0, 1.0);
    int calls = 0;
    while (calls < 4 * UpdateList::kIdleCalls + 2 && !sync.lastStats().alongList) {
        sync.sync(local);
        ++calls;
    }
    EXPECT_TRUE(sync.lastStats().alongList) << "after " << calls << " calls";
    EXPECT_EQ(globalMasters(local, world), 120u);
    auto const v = checkSyncInvariants(local, world, true, kSkin);
    EXPECT_TRUE(v.empty()) << joined(v);
}

TEST(UpdateList, AnIdleCallLeavesEveryShadowWithItsMastersHistory) {
    // Hybrid on a periodic row of 4 x 1 x 1 blocks, the last refined once (so y and z do not
    // wrap: its children do not span them): blocks 0 to 2 hold the y and z images of their
    // masters (shadows in their master's storage, which share its history while the list
    // holds). An SOS-class grain in block 0 reaches blocks 3, 0 and 1 only: the rank of block
    // 2 keeps a valid list at each refresh and shares, then acts on the others' Idle verdict.
    Comm world;
    AABB const domain{Vec3::Zero(), Vec3(8, 8, 8)};
    domain::ForestSpec spec = forestSpec(domain.min, domain.max, {4, 1, 1}, allAxes(true));
    spec.refine.push_back({AABB{Vec3(6.5, 0.5, 0.5), Vec3(7.5, 7.5, 7.5)}, 1});
    domain::BlockForest forest(world, spec);
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::Hybrid, false, kSkin});
    addAll(local, world, randomGas(domain, 120, 0.2, 0.6, 0.0, 11));
    addAll(local, world, {grain(makeUid(1, 0), Vec3(1.0, 4.0, 4.0), 2.2)});
    sync.syncUntilConverged(local);
    Uid const partner = makeUid(9, 9);
    std::size_t checked = 0;
    for (int stretch = 1; stretch <= 2; ++stretch) {
        // To the end of the idle stretch: the refresh tried again.
        int calls = 0;
        do {
            sync.sync(local);
        } while (sync.lastStats().skinIdle && ++calls < 4 * UpdateList::kIdleCalls);
        ASSERT_FALSE(sync.lastStats().skinIdle) << "stretch " << stretch;
        // Springs the masters' pairs write, then the first idle call after the refresh.
        for (BlockParticles& bp : local.blocks())
            bp.particles.forEachMaster([&](std::size_t m) {
                bp.particles.pairHistory(m).set(HistoryEntry{partner, Vec3(stretch, 0.0, 0.0),
                                                             static_cast<std::uint32_t>(stretch)});
            });
        sync.sync(local);
        ASSERT_TRUE(sync.lastStats().skinIdle) << "stretch " << stretch;
        for (BlockParticles const& bp : local.blocks()) {
            ParticleStorage const& ps = bp.particles;
            for (std::size_t k = 0; k < ps.size(); ++k) {
                std::size_t const m = ps.find(ps.uid(k));
                if (!ps.flags(k).isShadow() || m == ParticleStorage::kNotFound ||
                    !ps.flags(m).isMaster())
                    continue;
                // Not ASSERT: every rank goes on to the same collective calls.
                HistoryEntry const* own = ps.history(k).find(partner);
                EXPECT_FALSE(ps.sharesHistory(k)) << "uid " << ps.uid(k);
                EXPECT_TRUE(own != nullptr && own->spring == Vec3(stretch, 0.0, 0.0))
                    << "uid " << ps.uid(k) << ", stretch " << stretch
                    << ": the shadow's own history is not its master's";
                ++checked;
            }
        }
    }
    EXPECT_GT(world.allReduce(checked, regolith::core::ReduceOp::Sum), 0u);
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
