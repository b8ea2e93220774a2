// The invariant checker finds what it promises to find: a consistent state passes, and each
// kind of damage done on purpose to a synchronised state is reported, with the same list on
// every rank, whichever rank holds the damaged copy.
#include "core/Error.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <functional>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::ReduceOp;

namespace {

Uid const kGrain = makeUid(0, 1);  ///< at (9.5, 5.2, 5.3), r = 1: a shadow across x = 10
Uid const kOther = makeUid(0, 2);  ///< at (15.1, 14.6, 4.7), r = 0.8: no shadow
Uid const kCorner = makeUid(0, 3); ///< at (10.4, 10.3, 9.6), r = 1: copies in all 8 blocks

/// A synchronised 2x2x2 forest of edge-10 blocks with three grains, damaged by `damage`
/// (called on every rank), then checked.
std::vector<std::string> damaged(std::function<void(LocalParticles&, Comm const&)> const& damage,
                                 bool periodic = false) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(20), {2, 2, 2}, allAxes(periodic)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::NextNeighbour, false});
    addAll(local, world,
           {grain(kGrain, Vec3(9.5, 5.2, 5.3), 1.0), grain(kOther, Vec3(15.1, 14.6, 4.7), 0.8),
            grain(kCorner, Vec3(10.4, 10.3, 9.6), 1.0)});
    sync.syncUntilConverged(local);
    damage(local, world);
    return checkSyncInvariants(local, world, true);
}

bool mentions(std::vector<std::string> const& v, std::string const& a, std::string const& b) {
    for (std::string const& s : v)
        if (s.find(a) != std::string::npos && s.find(b) != std::string::npos)
            return true;
    return false;
}

std::string uidText(Uid uid) {
    return "uid " + std::to_string(uid) + ":";
}

/// Calls f(bp, i) for every shadow of `uid` on this rank.
template <class F>
void forShadows(LocalParticles& local, Uid uid, F&& f) {
    for (BlockParticles& bp : local.blocks()) {
        std::size_t const i = bp.particles.find(uid);
        if (i != ParticleStorage::kNotFound && bp.particles.flags(i).isShadow())
            f(bp, i);
    }
}

/// The verdict is the same list on every rank.
void expectSameEverywhere(std::vector<std::string> const& v) {
    Comm world;
    std::string const text = joined(v);
    auto const all = world.gatherStrings(text, 0);
    for (std::string const& s : all)
        EXPECT_EQ(s, text);
}

} // namespace

TEST(InvariantChecker, ConsistentStatePasses) {
    for (bool periodic : {false, true}) {
        auto const v = damaged([](LocalParticles&, Comm const&) {}, periodic);
        EXPECT_TRUE(v.empty()) << joined(v);
    }
}

TEST(InvariantChecker, MissingShadowIsReportedOnBothSides) {
    auto const v = damaged([](LocalParticles& local, Comm const&) {
        forShadows(local, kGrain,
                   [](BlockParticles& bp, std::size_t i) { bp.particles.remove(i); });
    });
    EXPECT_TRUE(mentions(v, uidText(kGrain), "holds no copy")) << joined(v);
    EXPECT_TRUE(mentions(v, uidText(kGrain), "which holds no shadow")) << joined(v);
    expectSameEverywhere(v);
}

TEST(InvariantChecker, ShadowOffByOneUlpIsReported) {
    auto const v = damaged([](LocalParticles& local, Comm const&) {
        forShadows(local, kGrain, [](BlockParticles& bp, std::size_t i) {
            double& x = bp.particles.position(i)[1];
            x = std::nextafter(x, 100.0);
        });
    });
    EXPECT_TRUE(mentions(v, uidText(kGrain), "differs from its master in position")) << joined(v);
    EXPECT_EQ(v.size(), 1U) << joined(v);
    expectSameEverywhere(v);
}

TEST(InvariantChecker, WrongOwnerAndVelocityAreReported) {
    auto const v = damaged([](LocalParticles& local, Comm const&) {
        forShadows(local, kGrain, [](BlockParticles& bp, std::size_t i) {
            bp.particles.setOwner(i, BlockRef{0, 12345});
            bp.particles.velocity(i)[0] = 1.0;
        });
    });
    EXPECT_TRUE(mentions(v, uidText(kGrain), "names owner")) << joined(v);
    EXPECT_TRUE(mentions(v, uidText(kGrain), "velocity")) << joined(v);
}

TEST(InvariantChecker, UnknownShadowIsReported) {
    auto const v = damaged([](LocalParticles& local, Comm const&) {
        if (auto [bp, i] = findMaster(local, kCorner); bp != nullptr)
            bp->particles.shadowHolders(i).pop_back();
    });
    EXPECT_TRUE(mentions(v, uidText(kCorner), "missing from the master's shadowHolders"))
        << joined(v);
    EXPECT_EQ(v.size(), 1U) << joined(v);
}

TEST(InvariantChecker, MasterOutsideItsBlockIsReported) {
    auto const v = damaged([](LocalParticles& local, Comm const&) {
        if (auto [bp, i] = findMaster(local, kOther); bp != nullptr)
            bp->particles.position(i)[0] = 9.0; // in another block, not synchronised
    });
    EXPECT_TRUE(mentions(v, uidText(kOther), "lies outside its block")) << joined(v);
}

TEST(InvariantChecker, CopyWhereTheGrainDoesNotReachIsReported) {
    // A complete, consistent shadow of kOther in the far block (0,0,1): only its presence is
    // wrong. Every rank learns the master's block first.
    auto const v = damaged([](LocalParticles& local, Comm const& comm) {
        auto [mbp, mi] = findMaster(local, kOther);
        std::array<std::int64_t, 3> owner{-1, -1, 0};
        if (mbp != nullptr)
            owner = {comm.rank(), static_cast<std::int64_t>(mbp->block->id.raw()), 1};
        comm.allReduceInPlace(std::span<std::int64_t>(owner), ReduceOp::Max);
        BlockRef const ref{static_cast<int>(owner[0]), static_cast<std::uint64_t>(owner[1])};
        domain::Block const* far = local.forest().localBlockContaining(Vec3(5, 5, 15));
        std::array<std::int64_t, 2> farRef{-1, -1};
        if (far != nullptr) {
            ParticleInit p = grain(kOther, Vec3(15.1, 14.6, 4.7), 0.8);
            p.flags = Flags(Flag::Shadow);
            p.owner = ref;
            local.find(far->id.raw())->particles.add(p);
            farRef = {comm.rank(), static_cast<std::int64_t>(far->id.raw())};
        }
        comm.allReduceInPlace(std::span<std::int64_t>(farRef), ReduceOp::Max);
        if (mbp != nullptr) {
            auto& h = mbp->particles.shadowHolders(mi);
            h.push_back(CopyRef{static_cast<int>(farRef[0]), static_cast<std::uint64_t>(farRef[1]),
                                kNoImage});
            std::sort(h.begin(), h.end());
        }
    });
    EXPECT_TRUE(mentions(v, uidText(kOther), "does not overlap it")) << joined(v);
    EXPECT_EQ(v.size(), 1U) << joined(v);
}

TEST(InvariantChecker, SecondMasterAndOrphanShadowAreReported) {
    Uid const orphan = makeUid(3, 99);
    auto const v = damaged([orphan](LocalParticles& local, Comm const&) {
        // A second master of kCorner in the block holding (5, 5, 5), and a shadow of a uid
        // that has no master, both on the rank owning that block.
        if (domain::Block const* b = local.forest().localBlockContaining(Vec3(5, 5, 5))) {
            ParticleStorage& ps = local.find(b->id.raw())->particles;
            ps.removeUid(kCorner);
            ParticleInit p = grain(kCorner, Vec3(5, 5, 5), 1.0);
            p.owner = BlockRef{local.forest().rank(), b->id.raw()};
            ps.add(p);
            ParticleInit s = grain(orphan, Vec3(5, 5, 6), 1.0);
            s.flags = Flags(Flag::Shadow);
            ps.add(s);
        }
    });
    EXPECT_TRUE(mentions(v, uidText(kCorner), "a second master")) << joined(v);
    EXPECT_TRUE(mentions(v, uidText(orphan), "no master")) << joined(v);
    expectSameEverywhere(v);
}

// SOS-class grains spread one block layer per call: before convergence the missing copies
// are reported only when the caller says spreading has converged.
TEST(InvariantChecker, SpreadingGrainsAreJudgedOnlyWhenConverged) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3(40, 10, 10), {4, 1, 1}, allAxes(false)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::ShadowOwner, false});
    Uid const big = makeUid(0, 7);
    addAll(local, world, {grain(big, Vec3(5.5, 5, 5), 25.0)}); // reaches block 3, k = 3
    sync.sync(local);
    auto const lenient = checkSyncInvariants(local, world, false);
    EXPECT_TRUE(lenient.empty()) << joined(lenient);
    auto const strict = checkSyncInvariants(local, world, true);
    EXPECT_TRUE(mentions(strict, uidText(big), "holds no copy")) << joined(strict);
    int const calls = sync.syncUntilConverged(local);
    EXPECT_GE(calls, 2);
    auto const after = checkSyncInvariants(local, world, true);
    EXPECT_TRUE(after.empty()) << joined(after);
}

TEST(InvariantChecker, RequireThrowsTheSameErrorEverywhere) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(20), {2, 2, 2}, allAxes(false)));
    LocalParticles local(forest);
    addAll(local, world, {grain(kGrain, Vec3(9.5, 5.2, 5.3), 1.0)}); // never synchronised
    std::string msg;
    try {
        requireSyncInvariants(local, world, true, "test");
    } catch (regolith::core::Error const& e) {
        msg = e.what();
    }
    EXPECT_NE(msg.find("(test)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("holds no copy"), std::string::npos) << msg;
    for (std::string const& s : world.gatherStrings(msg, 0))
        EXPECT_EQ(s, msg);
    // The step loop's hook checks in builds with REGOLITH_CHECK_INVARIANTS, else does nothing.
    if constexpr (kCheckSyncInvariants) {
        EXPECT_THROW(checkSyncInvariantsIfEnabled(local, world, true, "hook"),
                     regolith::core::Error);
    } else {
        EXPECT_NO_THROW(checkSyncInvariantsIfEnabled(local, world, true, "hook"));
    }
}
