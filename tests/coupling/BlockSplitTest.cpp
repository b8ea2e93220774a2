// Blocks that split where the load gathers (coupling/balance/BlockSplit.hpp): every block
// heavier than the share of a rank's mean load is split until the limits stop it, the grains' load
// is the same on the split forest, and every rank computes the same forest; where no block alone
// outweighs the floor, a split is taken only if its cut costs the busiest rank less, shadows
// counted (coupling/balance/CutSurface.hpp).
#include "coupling/balance/BlockSplit.hpp"

#include "coupling/balance/CutSurface.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

using namespace regolith;
using namespace regolith::particles::synctest;

namespace {

/// 4 x 1 x 1 blocks of edge 1; 300 grains spread over the plane z = 1/2 of block 0 (a
/// Kronecker sequence), 3 in every other block.
std::vector<particles::ParticleInit> crowdInFirstBlock(double radius) {
    std::vector<particles::ParticleInit> grains;
    particles::Uid uid = 0;
    auto const spread = [](int k, double step) {
        double const f = k * step;
        return 0.01 + 0.98 * (f - std::floor(f));
    };
    for (int b = 0; b < 4; ++b)
        for (int k = 0, n = b == 0 ? 300 : 3; k < n; ++k)
            grains.push_back(grain(
                uid++, Vec3(b + spread(k, 0.6180339887), spread(k, 0.7548776662), 0.5), radius));
    return grains;
}

struct CrowdedRow {
    Comm world;
    domain::ForestSpec spec = forestSpec(Vec3::Zero(), Vec3(4, 1, 1), {4, 1, 1}, allAxes(false));
    domain::BlockForest forest{world, spec};
    particles::LocalParticles local{forest};
    explicit CrowdedRow(double radius = 0.001) { addAll(local, world, crowdInFirstBlock(radius)); }
};

/// P + 1 blocks of edge 1 in a row on P ranks, `perBlock` grains in each, placed by `at(block,
/// k)`: every block below a rank's share, yet some rank holds two of them in any cut of whole
/// blocks (on one rank the cut is even).
struct RowOfEqualBlocks {
    Comm world;
    int blocks = world.size() + 1;
    domain::ForestSpec spec =
        forestSpec(Vec3::Zero(), Vec3(blocks, 1, 1), {blocks, 1, 1}, allAxes(false));
    domain::BlockForest forest{world, spec};
    particles::LocalParticles local{forest};
    template <class At>
    RowOfEqualBlocks(int perBlock, At&& at) {
        std::vector<particles::ParticleInit> grains;
        particles::Uid uid = 0;
        for (int b = 0; b < blocks; ++b)
            for (int k = 0; k < perBlock; ++k)
                grains.push_back(grain(uid++, at(b, k), 0.001));
        addAll(local, world, grains);
    }
};

double total(std::vector<double> const& load) {
    return std::accumulate(load.begin(), load.end(), 0.0);
}

} // namespace

TEST(BlockSplit, HeavyBlocksSplitUntilNoneExceedsTheShare) {
    CrowdedRow run;
    coupling::SplitLimits limits{0.5, 0.1, 6};
    coupling::SplitForest const split = coupling::splitHeavyBlocks(
        run.world, run.local, run.local.contactsStamped(0), {}, run.spec, limits);
    domain::ForestBuilder const builder(split.spec);
    EXPECT_GT(split.splits, 0u);
    EXPECT_EQ(builder.leaves().size(), 4 + 7 * split.splits);
    std::vector<double> const load =
        coupling::leafLoads(run.world, run.local, run.local.contactsStamped(0), {}, builder);
    double const mean = total(load) / run.world.size();
    // Every leaf weighs 1 + its grains: the grains are all counted, each once.
    EXPECT_DOUBLE_EQ(total(load), static_cast<double>(load.size()) + 309.0);
    for (std::size_t l = 0; l < load.size(); ++l) {
        domain::ForestLeaf const& leaf = builder.leaves()[l];
        EXPECT_TRUE(load[l] <= limits.share * mean || leaf.id.level() == limits.deepestLevel)
            << "leaf " << l << " weighs " << load[l] << " at level " << leaf.id.level();
        // Two blocks from the crowd, beyond its neighbours' 2:1 balance, nothing splits.
        if (builder.geometry().box(leaf.box).min.x() >= 2.0) {
            EXPECT_EQ(leaf.id.level(), 0) << "leaf " << l;
        }
    }
    // The same forest on every rank.
    auto const leaves = static_cast<long long>(builder.leaves().size());
    EXPECT_EQ(run.world.allReduce(leaves, core::ReduceOp::Min),
              run.world.allReduce(leaves, core::ReduceOp::Max));
}

TEST(BlockSplit, LimitsStopTheSplits) {
    CrowdedRow run;
    auto const splitsWith = [&](coupling::SplitLimits const& limits) {
        return coupling::splitHeavyBlocks(run.world, run.local, run.local.contactsStamped(0), {},
                                          run.spec, limits)
            .splits;
    };
    EXPECT_EQ(splitsWith({0.5, 0.1, 0}), 0u); // no level below the scene's
    EXPECT_EQ(splitsWith({0.5, 0.1, 1}), 1u); // one level: the crowded block alone
    EXPECT_EQ(splitsWith({4.0, 0.1, 6}), 0u); // no block above four shares: whole blocks do
    // Grains of diameter 0.6: children of edge 0.5 would be narrower.
    CrowdedRow wide(0.3);
    EXPECT_EQ(coupling::splitHeavyBlocks(wide.world, wide.local, wide.local.contactsStamped(0), {},
                                         wide.spec, {0.5, 0.1, 6})
                  .splits,
              0u);
}

TEST(BlockSplit, WeightsOfTheSplitForestCountItsBlocksGrains) {
    CrowdedRow run;
    coupling::SplitForest const split = coupling::splitHeavyBlocks(
        run.world, run.local, run.local.contactsStamped(0), {}, run.spec, {0.5, 0.1, 1});
    domain::BlockWeight const weight = coupling::grainAndCellWeights(
        run.world, run.local, run.local.contactsStamped(0), {}, split.spec);
    domain::ForestBuilder const builder(split.spec);
    double sum = 0.0;
    for (domain::ForestLeaf const& leaf : builder.leaves()) {
        core::AABB const box = builder.geometry().box(leaf.box);
        double const w = weight(box, leaf.id.level());
        EXPECT_GE(w, 1.0);
        if (box.min.x() >= 1.0) {
            EXPECT_DOUBLE_EQ(w, 4.0) << "block at x = " << box.min.x();
        }
        sum += w;
    }
    EXPECT_DOUBLE_EQ(sum, static_cast<double>(builder.leaves().size()) + 309.0);
}

TEST(BlockSplit, LighterBlocksSplitWhereTheSplitCutCostsLess) {
    // Grains spread over each block: the split's cut evens the ranks, few grains on its faces.
    auto const spread = [](int b, int k) {
        auto const frac = [](double f) { return 0.01 + 0.98 * (f - std::floor(f)); };
        return Vec3(b + frac(k * 0.6180339887), frac(k * 0.7548776662), frac(k * 0.5698402910));
    };
    RowOfEqualBlocks run(60, spread);
    std::size_t const splits =
        coupling::splitHeavyBlocks(run.world, run.local, run.local.contactsStamped(0), {}, run.spec,
                                   {1.05, 0.1, 3})
            .splits;
    if (run.world.size() == 1)
        EXPECT_EQ(splits, 0u); // one rank: whole blocks are even
    else
        EXPECT_GT(splits, 0u);
}

TEST(BlockSplit, LighterBlocksStayWholeWhereTheSplitCutCostsMore) {
    // Each block's grains in one point: a split cannot part them, its cut is no better and has
    // more blocks, so the whole blocks are kept (a heavier block than the floor would split).
    RowOfEqualBlocks run(60, [](int b, int) { return Vec3(b + 0.3, 0.3, 0.3); });
    EXPECT_EQ(coupling::splitHeavyBlocks(run.world, run.local, run.local.contactsStamped(0), {},
                                         run.spec, {1.05, 0.1, 3})
                  .splits,
              0u);
    EXPECT_GT(coupling::splitHeavyBlocks(run.world, run.local, run.local.contactsStamped(0), {},
                                         run.spec, {0.4, 0.1, 3})
                  .splits,
              0u);
}

TEST(CutSurface, ARankPaysForTheShadowsOfGrainsReachingItsBlocks) {
    // Two blocks; a grain of block 0 reaches across the face into block 1, another does not.
    Comm world;
    domain::ForestSpec const spec =
        forestSpec(Vec3::Zero(), Vec3(2, 1, 1), {2, 1, 1}, allAxes(false));
    domain::BlockForest forest{world, spec};
    particles::LocalParticles local{forest};
    addAll(local, world, {grain(0, Vec3(0.95, 0.5, 0.5), 0.1), grain(1, Vec3(0.5, 0.5, 0.5), 0.1)});
    domain::ForestBuilder const builder(spec);
    std::vector<double> const load{3.0, 5.0};
    int const second = std::min(1, world.size() - 1);
    std::vector<int> const owner{0, second};
    std::vector<double> const cost =
        coupling::rankCosts(world, local, local.contactsStamped(0), {}, builder, load, owner);
    ASSERT_EQ(cost.size(), static_cast<std::size_t>(world.size()));
    if (second == 0) {
        EXPECT_DOUBLE_EQ(cost[0], 8.0); // one rank, one cuboid: no shadow
    } else {
        EXPECT_DOUBLE_EQ(cost[0], 3.0);
        EXPECT_DOUBLE_EQ(cost[1], 6.0); // its load and the shadow of grain 0
    }
}
