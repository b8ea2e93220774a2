// The particles' subdomains (Subdomains::RankBoxes): each rank's blocks merged into cuboids.
// The forest queries and links of merged forests are checked with the others (ForestQuery,
// ForestTopology, the "Merged" cases); this file checks what the merge itself promises.
#include "domain/RankBoxes.hpp"

#include "domain/BlockForest.hpp"
#include "tests/domain/GlobalForest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace regolith;
using namespace regolith::domain;
using namespace regolith::domain::test;

namespace {

class RankBoxes : public ::testing::TestWithParam<ForestCase> {};

LatticeIndex volume(LatticeBox const& b) {
    return (b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]);
}

bool inside(LatticeBox const& inner, LatticeBox const& outer) {
    for (int a = 0; a < 3; ++a)
        if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a])
            return false;
    return true;
}

} // namespace

TEST_P(RankBoxes, EachBoxIsExactlyTiledByLeavesOfItsRank) {
    ForestBuilder builder(GetParam().spec);
    for (int ranks : {1, 2, 3, 5, 8}) {
        builder.assign(randomWeight, ranks);
        auto const& leaves = builder.leaves();
        SubdomainCut const cut = mergeRankLeaves(leaves);
        std::vector<RankBox> const& boxes = cut.boxes;
        std::vector<int> covered(leaves.size(), 0);
        for (RankBox const& box : boxes) {
            LatticeIndex sum = 0;
            auto const mine = cut.leavesOf(box);
            ASSERT_FALSE(mine.empty());
            EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
            for (std::uint32_t l : mine) {
                ++covered[l];
                EXPECT_EQ(leaves[l].owner, box.owner) << leaves[l].id;
                EXPECT_TRUE(inside(leaves[l].box, box.lattice)) << leaves[l].id;
                sum += volume(leaves[l].box);
            }
            EXPECT_EQ(sum, volume(box.lattice)) << "leaves overlap or leave a gap";
        }
        EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }))
            << ranks << " ranks: a leaf in no box or in two";
        for (std::size_t b = 1; b < boxes.size(); ++b)
            EXPECT_LT(cut.leavesOf(boxes[b - 1]).front(), cut.leavesOf(boxes[b]).front());
    }
}

TEST_P(RankBoxes, ARankWhoseLeavesFormACuboidGetsOneBox) {
    ForestBuilder builder(GetParam().spec);
    for (int ranks : {1, 2, 4, 8}) {
        builder.assign({}, ranks);
        auto const& leaves = builder.leaves();
        std::vector<RankBox> const boxes = mergeRankLeaves(leaves).boxes;
        for (int r = 0; r < ranks; ++r) {
            LatticeBox hull{{1LL << 62, 1LL << 62, 1LL << 62},
                            {-(1LL << 62), -(1LL << 62), -(1LL << 62)}};
            LatticeIndex sum = 0;
            for (ForestLeaf const& l : leaves) {
                if (l.owner != r)
                    continue;
                for (int a = 0; a < 3; ++a) {
                    hull.lo[a] = std::min(hull.lo[a], l.box.lo[a]);
                    hull.hi[a] = std::max(hull.hi[a], l.box.hi[a]);
                }
                sum += volume(l.box);
            }
            auto const mine = std::count_if(boxes.begin(), boxes.end(),
                                            [r](RankBox const& b) { return b.owner == r; });
            if (sum > 0 && sum == volume(hull) && GetParam().spec.refine.empty()) {
                EXPECT_EQ(mine, 1) << ranks << " ranks, rank " << r;
            }
            if (sum == 0) {
                EXPECT_EQ(mine, 0);
            }
        }
    }
}

TEST_P(RankBoxes, TheLeafContainingAPointIsTheForestsBlock) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const blocks(world, spec);
    BlockForest const merged(world, spec, {}, Subdomains::RankBoxes);
    EXPECT_EQ(merged.globalBlockCount(), blocks.globalBlockCount());
    EXPECT_LE(merged.globalSubdomainCount(), blocks.globalSubdomainCount());
    EXPECT_EQ(merged.neighbourRanks(), blocks.neighbourRanks());
    std::size_t leaves = 0;
    for (Block const& b : merged.blocks())
        leaves += b.leaves.size();
    EXPECT_EQ(leaves, blocks.blocks().size());

    std::mt19937_64 rng(11);
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
        core::Vec3 p;
        for (int a = 0; a < 3; ++a)
            p[a] =
                std::uniform_real_distribution<double>(spec.domain.min[a], spec.domain.max[a])(rng);
        Block const* leaf = blocks.localBlockContaining(p);
        Block const* box = merged.localBlockContaining(p);
        ASSERT_EQ(leaf == nullptr, box == nullptr) << p.transpose();
        if (box == nullptr)
            continue;
        ++checked;
        EXPECT_TRUE(box->aabb.contains(p));
        CoveredLeaf const& c = box->leaves[merged.leafContaining(*box, p)];
        EXPECT_EQ(c.id, leaf->id) << p.transpose();
        EXPECT_EQ(merged.findBlock(leaf->id), box);
    }
    EXPECT_EQ(world.allReduce(checked, core::ReduceOp::Sum), 2000);
}

INSTANTIATE_TEST_SUITE_P(Cases, RankBoxes, ::testing::ValuesIn(forestCases()),
                         [](auto const& c) { return c.param.name; });
