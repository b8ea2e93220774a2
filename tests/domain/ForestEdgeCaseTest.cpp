// Forests at the edges of the design space, with exact expected neighbourhoods: one and two
// blocks across periodic axes (self-links, repeated neighbours), refined next to coarse,
// extreme aspect ratios, more ranks than blocks, and a large root grid.
#include "domain/BlockForest.hpp"
#include "domain/ForestBuilder.hpp"
#include "tests/domain/GlobalForest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

using namespace regolith;
using namespace regolith::domain;
using namespace regolith::domain::test;

namespace {

ForestSpec makeSpec(core::Vec3 lo, core::Vec3 hi, std::array<int, 3> n, std::array<bool, 3> p) {
    ForestSpec s;
    s.domain = {lo, hi};
    s.rootBlocks = n;
    s.periodic = p;
    return s;
}

/// Links of `b` grouped by neighbour id: id -> set of images.
std::map<BlockId, std::set<PeriodicImage>> imagesById(Block const& b) {
    std::map<BlockId, std::set<PeriodicImage>> out;
    for (BlockLink const& l : b.neighbours)
        EXPECT_TRUE(out[l.id].insert(l.image).second) << "duplicate link in " << b.id;
    return out;
}

} // namespace

TEST(ForestEdgeCases, SingleFullyPeriodicBlockHas26SelfLinks) {
    core::Comm world;
    BlockForest const forest(world, makeSpec({0, 0, 0}, {2, 3, 4}, {1, 1, 1}, {true, true, true}));
    EXPECT_EQ(forest.globalBlockCount(), 1U);
    EXPECT_EQ(forest.idleRankCount(), world.size() - 1);
    EXPECT_EQ(world.allReduce(forest.isIdle() ? 0 : 1, core::ReduceOp::Sum), 1);
    EXPECT_TRUE(forest.neighbourRanks().empty());
    for (Block const& b : forest.blocks()) {
        auto const byId = imagesById(b);
        ASSERT_EQ(byId.size(), 1U);
        EXPECT_EQ(byId.begin()->first, b.id);
        EXPECT_EQ(byId.begin()->second.size(), 26U);
        EXPECT_EQ(byId.begin()->second.count(PeriodicImage{0, 0, 0}), 0U);
        for (BlockLink const& l : b.neighbours)
            EXPECT_EQ(l.shift, core::Vec3(-2.0 * l.image[0], -3.0 * l.image[1], -4.0 * l.image[2]));
        // A point just below the lower x face is the block's own image across the boundary.
        auto const got = forest.blockContaining(b, {-0.25, 1.0, 1.0});
        ASSERT_TRUE(got.has_value());
        EXPECT_EQ(got->id, b.id);
        EXPECT_EQ(got->image, (PeriodicImage{-1, 0, 0}));
        EXPECT_EQ(got->shift, core::Vec3(2.0, 0.0, 0.0));
    }
}

TEST(ForestEdgeCases, TwoBlocksAcrossPeriodicAxisListEachOtherTwice) {
    core::Comm world;
    BlockForest const forest(world,
                             makeSpec({0, 0, 0}, {2, 1, 1}, {2, 1, 1}, {true, false, false}));
    for (Block const& b : forest.blocks()) {
        ASSERT_EQ(b.neighbours.size(), 2U) << b.id;
        BlockId const other = BlockId::root(1 - b.id.rootIndex());
        int const across = b.id.rootIndex() == 0 ? -1 : 1; // block 0 sees block 1 below x = 0
        EXPECT_EQ(imagesById(b),
                  (std::map<BlockId, std::set<PeriodicImage>>{
                      {other, {PeriodicImage{0, 0, 0}, PeriodicImage{across, 0, 0}}}}));
        for (BlockLink const& l : b.neighbours)
            EXPECT_EQ(l.shift[0], l.image[0] == 0 ? 0.0 : -2.0 * across);
    }
}

TEST(ForestEdgeCases, TwoBlocksFullyPeriodicHave18OtherAnd8SelfLinks) {
    core::Comm world;
    BlockForest const forest(world, makeSpec({0, 0, 0}, {2, 1, 1}, {2, 1, 1}, {true, true, true}));
    for (Block const& b : forest.blocks()) {
        auto const byId = imagesById(b);
        ASSERT_EQ(byId.size(), 2U);
        EXPECT_EQ(byId.at(b.id).size(), 8U);
        EXPECT_EQ(byId.at(BlockId::root(1 - b.id.rootIndex())).size(), 18U);
        EXPECT_EQ(b.neighbours.size(), 26U);
    }
}

TEST(ForestEdgeCases, CoarseBlockSeesTheFourChildrenOfItsRefinedNeighbour) {
    core::Comm world;
    ForestSpec spec = makeSpec({0, 0, 0}, {4, 1, 1}, {4, 1, 1}, {false, false, false});
    spec.refine.push_back({{core::Vec3(0.1, 0.1, 0.1), core::Vec3(0.9, 0.9, 0.9)}, 1});
    BlockForest const forest(world, spec);
    EXPECT_EQ(forest.globalBlockCount(), 8U + 3U);
    auto const all = gatherBlocks(world, forest);
    for (GlobalBlock const& g : all) {
        if (g.block.id != BlockId::root(1))
            continue;
        std::set<BlockId> expected{BlockId::root(2)};
        for (int k = 1; k < 8; k += 2) // children in the upper x half of root 0
            expected.insert(BlockId::root(0).child(k));
        std::set<BlockId> got;
        for (BlockLink const& l : g.block.neighbours) {
            got.insert(l.id);
            EXPECT_EQ(l.level, l.id == BlockId::root(2) ? 0 : 1);
        }
        EXPECT_EQ(got, expected);
    }
}

TEST(ForestEdgeCases, BalanceRipplesAcrossThePeriodicBoundary) {
    // Level 3 at the lower corner of a fully periodic 4x1x1 row: the level-1 blocks needed by
    // 2:1 balance must appear in root 3, on the other side of the periodic x boundary.
    ForestSpec spec = makeSpec({0, 0, 0}, {4, 1, 1}, {4, 1, 1}, {true, true, true});
    spec.refine.push_back({{core::Vec3(0, 0.5, 0.5), core::Vec3(0, 0.5, 0.5)}, 3});
    ForestBuilder const builder(spec);
    bool root3Refined = false;
    bool root2Refined = false;
    for (ForestLeaf const& l : builder.leaves()) {
        root3Refined = root3Refined || (l.id.rootIndex() == 3 && l.id.level() > 0);
        root2Refined = root2Refined || (l.id.rootIndex() == 2 && l.id.level() > 0);
    }
    EXPECT_TRUE(root3Refined);
    EXPECT_FALSE(root2Refined);
}

TEST(ForestEdgeCases, LongThinDomainAlongX) {
    core::Comm world;
    BlockForest const forest(world,
                             makeSpec({0, 0, 0}, {1000, 1, 1}, {100, 1, 1}, {true, false, false}));
    EXPECT_EQ(forest.globalBlockCount(), 100U);
    for (Block const& b : forest.blocks()) {
        EXPECT_DOUBLE_EQ(b.aabb.extent()[0], 10.0);
        ASSERT_EQ(b.neighbours.size(), 2U) << b.id;
        std::set<std::uint64_t> roots;
        for (BlockLink const& l : b.neighbours)
            roots.insert(l.id.rootIndex());
        std::uint64_t const i = b.id.rootIndex();
        EXPECT_EQ(roots, (std::set<std::uint64_t>{(i + 99) % 100, (i + 1) % 100}));
        if (i == 0) { // the point just left of x = 0 is block 99, across the boundary
            auto const got = forest.blockContaining(b, {-0.001, 0.5, 0.5});
            ASSERT_TRUE(got.has_value());
            EXPECT_EQ(got->id, BlockId::root(99));
            EXPECT_EQ(got->shift, core::Vec3(1000, 0, 0));
        }
    }
}

TEST(ForestEdgeCases, FlatBlocksAlongZ) {
    core::Comm world;
    BlockForest const forest(world, makeSpec({0, 0, 0}, {1, 1, 1}, {1, 1, 64}, {true, true, true}));
    for (Block const& b : forest.blocks()) {
        EXPECT_DOUBLE_EQ(b.aabb.extent()[2], 1.0 / 64.0);
        auto const byId = imagesById(b);
        EXPECT_EQ(byId.size(), 3U);
        EXPECT_EQ(byId.at(b.id).size(), 8U);
        EXPECT_EQ(b.neighbours.size(), 26U);
    }
}

TEST(ForestEdgeCases, MoreRanksThanBlocksLeavesRanksIdle) {
    core::Comm world;
    BlockForest const forest(world,
                             makeSpec({0, 0, 0}, {2, 1, 1}, {2, 1, 1}, {false, false, false}));
    int const p = world.size();
    EXPECT_EQ(forest.idleRankCount(), std::max(0, p - 2));
    int const idle = world.allReduce(forest.isIdle() ? 1 : 0, core::ReduceOp::Sum);
    EXPECT_EQ(idle, forest.idleRankCount());
    EXPECT_EQ(forest.isIdle(), forest.blocks().empty());
    if (forest.isIdle()) {
        EXPECT_EQ(forest.localBlockContaining({0.5, 0.5, 0.5}), nullptr);
        EXPECT_EQ(forest.localBlockContaining({1.5, 0.5, 0.5}), nullptr);
        EXPECT_TRUE(forest.neighbourRanks().empty());
    }
    auto const all = gatherBlocks(world, forest);
    ASSERT_EQ(all.size(), 2U);
    EXPECT_EQ(all[0].heldBy == all[1].heldBy, p == 1);
}

TEST(ForestEdgeCases, LargeRootGridHasFullNeighbourhoods) {
    // 64^3 root blocks: every block of a fully periodic grid has exactly 26 distinct
    // neighbours. Each rank checks its share of the leaves with the builder directly.
    core::Comm world;
    ForestBuilder builder(makeSpec({0, 0, 0}, {64, 64, 64}, {64, 64, 64}, {true, true, true}));
    ASSERT_EQ(builder.leaves().size(), 64U * 64U * 64U);
    std::vector<LeafLink> links;
    int wrong = 0;
    for (std::size_t i = static_cast<std::size_t>(world.rank()); i < builder.leaves().size();
         i += static_cast<std::size_t>(world.size())) {
        builder.neighbours(i, links);
        std::set<std::uint32_t> distinct;
        for (LeafLink const& l : links)
            distinct.insert(l.leaf);
        wrong += (links.size() != 26 || distinct.size() != 26) ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0);
}

TEST(ForestEdgeCases, MediumForestOnRanksHasConsistentCounts) {
    core::Comm world;
    BlockForest const forest(world,
                             makeSpec({0, 0, 0}, {24, 24, 24}, {24, 24, 24}, {true, false, true}));
    long const local = static_cast<long>(forest.blocks().size());
    EXPECT_EQ(world.allReduce(local, core::ReduceOp::Sum), 24L * 24L * 24L);
    for (Block const& b : forest.blocks()) {
        LatticeCell const c = forest.geometry().rootCoord(b.id.rootIndex());
        std::size_t const ySpan = (c[1] == 0 || c[1] == 23) ? 2 : 3; // y is not periodic
        EXPECT_EQ(b.neighbours.size(), 9 * ySpan - 1) << b.id;
    }
}
