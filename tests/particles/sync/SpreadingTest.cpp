// Diffusive spreading (SOS, Eibl & Ruede 2018 Alg. 2, second round): a new grain that spans
// k block layers around its block has all its shadows after at most k calls of sync(); the
// copies that exist in between are consistent; afterwards one call per move keeps everything
// consistent. Open and periodic forests (periodic: a block holds several images of the grain).
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::ReduceOp;

namespace {

/// The largest Chebyshev distance, in root blocks of the unwrapped lattice, from the block
/// holding x to a block image the ball (x, r) reaches: the number of layers k. COLLECTIVE.
int layers(LocalParticles const& local, Comm const& comm, Vec3 const& x, double r) {
    domain::BlockForest const& forest = local.forest();
    domain::ForestGeometry const& g = forest.geometry();
    Vec3 const period = periodOf(forest);
    Vec3 const edge = forest.domain().extent().cwiseQuotient(
        Vec3(g.rootBlocks()[0], g.rootBlocks()[1], g.rootBlocks()[2]));
    Vec3 const home = (x - forest.domain().min).cwiseQuotient(edge).array().floor().matrix();
    int k = 0;
    for (BlockParticles const& bp : local.blocks()) {
        auto const c = g.rootCoord(bp.block->id.rootIndex());
        for (int i = -2; i <= 2; ++i)
            for (int j = -2; j <= 2; ++j)
                for (int l = -2; l <= 2; ++l) {
                    CopyImage const im{static_cast<std::int8_t>(period[0] > 0 ? i : 0),
                                       static_cast<std::int8_t>(period[1] > 0 ? j : 0),
                                       static_cast<std::int8_t>(period[2] > 0 ? l : 0)};
                    if (bp.block->aabb.sqDistance(localPosition(x, im, period)) >= r * r)
                        continue;
                    for (int a = 0; a < 3; ++a) {
                        // The image of block c at im is block c - im * n of the unwrapped lattice.
                        double const u = static_cast<double>(c[static_cast<std::size_t>(a)]) -
                                         im[static_cast<std::size_t>(a)] *
                                             g.rootBlocks()[static_cast<std::size_t>(a)];
                        k = std::max(k, static_cast<int>(std::abs(u - home[a])));
                    }
                }
    }
    return comm.allReduce(k, ReduceOp::Max);
}

void spread(SyncMethod method, bool periodic) {
    Comm world;
    // Open: 6^3 blocks of edge 10. Periodic: 4^3 blocks of edge 10, narrower than the grain.
    double const L = periodic ? 40.0 : 60.0;
    int const n = periodic ? 4 : 6;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(L), {n, n, n}, allAxes(periodic)));
    std::ostringstream label;
    label << methodName(method) << (periodic ? " periodic" : " open");
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{method, false});
    // A few small grains around, so that the big one is not alone in the exchanges.
    addAll(local, world, randomGas(forest.domain(), 40, 0.3, 0.6, 0.1, 3));
    sync.syncUntilConverged(local);

    Uid const big = makeUid(5, 0);
    Vec3 const x = periodic ? Vec3(20.5, 20.3, 19.6) : Vec3(30.5, 30.5, 30.5);
    double const r = 25.0;
    EXPECT_EQ(addAll(local, world, {grain(big, x, r)}), 1U);
    int const k = layers(local, world, x, r);
    EXPECT_EQ(k, 3) << label.str(); // the geometry chosen for this test
    int calls = 0;
    std::vector<std::string> v;
    do {
        sync.sync(local);
        ++calls;
        auto const partial = checkSyncInvariants(local, world, false);
        EXPECT_TRUE(partial.empty()) << label.str() << " call " << calls << joined(partial);
        v = checkSyncInvariants(local, world, true);
    } while (!v.empty() && calls < 10);
    EXPECT_TRUE(v.empty()) << label.str() << joined(v);
    EXPECT_LE(calls, k) << label.str() << ": all shadows after at most k calls";
    std::uint64_t const copies = expectPresence(local, big, x, r, label.str());
    EXPECT_GT(world.allReduce(copies, ReduceOp::Sum), 27U) << label.str();

    // One call per move keeps every copy where it belongs.
    Vec3 const step(0.7, -0.45, 0.3);
    for (int move = 1; move <= 20; ++move) {
        if (auto const [bp, i] = findMaster(local, big); bp != nullptr)
            bp->particles.position(i) += step;
        sync.sync(local);
        v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << label.str() << " move " << move << joined(v);
    }
    GrainView const g = viewGrain(local, world, big);
    EXPECT_LT((g.position - forest.wrap(x + 20 * step)).norm(), 1e-9) << label.str();
    expectPresence(local, big, g.position, r, label.str() + " after the moves");
}

} // namespace

TEST(Spreading, SosOpen) {
    spread(SyncMethod::ShadowOwner, false);
}

TEST(Spreading, SosPeriodic) {
    spread(SyncMethod::ShadowOwner, true);
}

TEST(Spreading, HybridOpen) {
    spread(SyncMethod::Hybrid, false);
}

TEST(Spreading, HybridPeriodic) {
    spread(SyncMethod::Hybrid, true);
}

TEST(Spreading, SyncUntilConvergedNeedsAtMostOneCallMoreThanTheLayers) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3(80, 20, 20), {8, 2, 2}, allAxes(false)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::ShadowOwner, false});
    Vec3 const x(15.5, 10.5, 9.5);
    addAll(local, world, {grain(makeUid(0, 1), x, 42.0)}); // reaches block 5: k = 4
    int const k = layers(local, world, x, 42.0);
    EXPECT_EQ(k, 4);
    int const calls = sync.syncUntilConverged(local);
    EXPECT_LE(calls, k + 1); // the last call only proves that nothing is created any more
    EXPECT_GE(calls, 2);
    auto const v = checkSyncInvariants(local, world, true);
    EXPECT_TRUE(v.empty()) << joined(v);
}

// A small SOS grain (its master's block and the neighbours hold the ball) is spread by its
// master alone, in round 1 (Flag::MasterReachesAll): when it newly reaches an edge block while
// it has a shadow across a face, only the master orders that copy -- with the shadows
// searching too, the face shadow ordered it as well and the receiver dropped a duplicate. Every
// call leaves every copy in place (no call is needed to converge).
TEST(Spreading, SosSmallGrainIsSpreadByItsMasterAlone) {
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3::Constant(30.0), {3, 3, 3}, allAxes(false)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::ShadowOwner, false});
    Uid const uid = makeUid(1, 0);
    double const r = 2.0;
    // In the centre block, its ball across the face x = 10 only.
    addAll(local, world, {grain(uid, Vec3(10.5, 14.25, 14.0), r)});
    sync.syncUntilConverged(local);
    for (int move = 1; move <= 6; ++move) { // down in y: across the face y = 10 at move 5
        if (auto const [bp, i] = findMaster(local, uid); bp != nullptr)
            bp->particles.position(i) += Vec3(0.0, -0.5, 0.0);
        sync.sync(local);
        std::uint64_t const created = world.allReduce(sync.lastStats().created, ReduceOp::Sum);
        std::uint64_t const duplicates =
            world.allReduce(sync.lastStats().duplicates, ReduceOp::Sum);
        EXPECT_EQ(duplicates, 0U) << "move " << move;
        if (move == 5) {
            EXPECT_EQ(created, 2U) << "the copies in the y- and the x-y- edge blocks";
        }
        auto const v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << "move " << move << joined(v);
        std::uint64_t shadows = 0, flagged = 0;
        for (BlockParticles const& bp : local.blocks())
            for (std::size_t i = 0; i < bp.particles.size(); ++i)
                if (bp.particles.uid(i) == uid && bp.particles.flags(i).isShadow()) {
                    ++shadows;
                    flagged += bp.particles.flags(i).has(Flag::MasterReachesAll) ? 1U : 0U;
                }
        EXPECT_EQ(world.allReduce(flagged, ReduceOp::Sum), world.allReduce(shadows, ReduceOp::Sum))
            << "move " << move;
        EXPECT_EQ(world.allReduce(shadows, ReduceOp::Sum), move < 5 ? 1U : 3U) << "move " << move;
    }
}
