// The forest as a whole, gathered on every rank: blocks tile the domain, neighbour links are
// complete, correct and symmetric, 2:1 balance holds, and the curve order and the weighted
// assignment are what ForestBuilder promises. Run on every case of forestCases().
#include "domain/BlockForest.hpp"
#include "domain/ForestBuilder.hpp"
#include "domain/HilbertCurve.hpp"
#include "tests/domain/GlobalForest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

using namespace regolith;
using namespace regolith::domain;
using namespace regolith::domain::test;

namespace {

/// Properties of every forest, blocks or merged subdomains (forestCasesBothWays).
class ForestTopology : public ::testing::TestWithParam<ForestCase> {};
/// Properties of the leaves themselves: refinement, balance, curve order, assignment.
class ForestLeaves : public ::testing::TestWithParam<ForestCase> {};

std::unordered_map<BlockId, GlobalBlock const*> byId(std::vector<GlobalBlock> const& all) {
    std::unordered_map<BlockId, GlobalBlock const*> map;
    for (GlobalBlock const& g : all)
        map.emplace(g.block.id, &g);
    return map;
}

PeriodicImage negated(PeriodicImage const& o) {
    return {-o[0], -o[1], -o[2]};
}

} // namespace

TEST_P(ForestTopology, BlocksTileTheDomain) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);

    double localVolume = 0.0;
    for (Block const& b : forest.blocks())
        localVolume += b.aabb.volume();
    double const volume = world.allReduce(localVolume, core::ReduceOp::Sum);
    EXPECT_NEAR(volume, spec.domain.volume(), 1e-12 * spec.domain.volume());

    auto const all = gatherBlocks(world, forest);
    EXPECT_EQ(all.size(), forest.globalSubdomainCount());
    auto const count =
        world.allReduce(static_cast<long>(forest.blocks().size()), core::ReduceOp::Sum);
    EXPECT_EQ(static_cast<std::size_t>(count), forest.globalSubdomainCount());

    std::set<std::uint64_t> ids;
    int overlaps = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        Block const& b = all[i].block;
        ids.insert(b.id.raw());
        EXPECT_EQ(b.owner, all[i].heldBy) << b.id;
        EXPECT_EQ(b.level, b.id.level()) << b.id;
        EXPECT_TRUE((b.aabb.min.array() >= spec.domain.min.array()).all() &&
                    (b.aabb.max.array() <= spec.domain.max.array()).all() &&
                    (b.aabb.min.array() < b.aabb.max.array()).all())
            << b.id;
        for (std::size_t j = i + 1; j < all.size(); ++j)
            overlaps += b.aabb.intersectsOpen(all[j].block.aabb) ? 1 : 0;
    }
    EXPECT_EQ(ids.size(), all.size());
    EXPECT_EQ(overlaps, 0);
}

TEST_P(ForestTopology, LinksAreSymmetricAndDescribeTheNeighbour) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);
    auto const map = byId(all);
    core::Vec3 const tol = 1e-6 * finestEdge(all);

    std::map<std::tuple<std::uint64_t, std::uint64_t, PeriodicImage>, int> multiplicity;
    for (GlobalBlock const& g : all) {
        for (BlockLink const& l : g.block.neighbours) {
            ++multiplicity[{g.block.id.raw(), l.id.raw(), l.image}];
            auto const it = map.find(l.id);
            ASSERT_NE(it, map.end()) << "link to unknown block " << l.id;
            Block const& n = it->second->block;
            EXPECT_EQ(l.aabb.min, n.aabb.min) << l.id;
            EXPECT_EQ(l.aabb.max, n.aabb.max) << l.id;
            EXPECT_EQ(l.owner, n.owner) << l.id;
            EXPECT_EQ(l.level, n.level) << l.id;
            EXPECT_EQ(l.shift, -translation(spec.domain, l.image)) << l.id;
            for (int a = 0; a < 3; ++a)
                EXPECT_TRUE(spec.periodic[a] || l.image[a] == 0) << l.id;
            EXPECT_TRUE(touchesWithin(l.imageBox(), g.block.aabb, tol))
                << g.block.id << " -> " << l.id;
        }
    }
    for (auto const& [key, n] : multiplicity) {
        auto const& [a, b, o] = key;
        auto const back = multiplicity.find({b, a, negated(o)});
        ASSERT_NE(back, multiplicity.end())
            << BlockId::fromRaw(b) << " does not list " << BlockId::fromRaw(a);
        EXPECT_EQ(back->second, n);
        EXPECT_EQ(n, 1) << "duplicate link " << BlockId::fromRaw(a) << " -> "
                        << BlockId::fromRaw(b);
    }
}

TEST_P(ForestTopology, LinksAreExactlyTheTouchingImages) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);
    for (Block const& b : forest.blocks()) {
        std::vector<LinkKey> got;
        for (BlockLink const& l : b.neighbours)
            got.push_back(LinkKey{l.id.raw(), l.image});
        std::sort(got.begin(), got.end());
        EXPECT_EQ(got, touchingImages(all, b, spec.domain, spec.periodic)) << b.id;
    }
}

TEST_P(ForestLeaves, TwoToOneBalanceAndRefinementReached) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec);
    auto const all = gatherBlocks(world, forest);

    int maxRequested = 0;
    for (RefineRegion const& r : spec.refine)
        maxRequested = std::max(maxRequested, r.level);
    EXPECT_EQ(forest.maxLevel(), maxRequested);

    bool levelJump = false;
    int deepest = 0;
    for (GlobalBlock const& g : all) {
        deepest = std::max(deepest, g.block.level);
        for (BlockLink const& l : g.block.neighbours) {
            EXPECT_LE(std::abs(l.level - g.block.level), 1) << g.block.id << " -> " << l.id;
            levelJump = levelJump || l.level != g.block.level;
        }
        for (RefineRegion const& r : spec.refine) {
            if (g.block.aabb.intersectsClosed(r.region)) {
                EXPECT_GE(g.block.level, r.level) << g.block.id;
            }
        }
    }
    EXPECT_EQ(deepest, maxRequested);
    EXPECT_EQ(levelJump, !spec.refine.empty()) << "refined blocks next to coarser ones";
}

TEST_P(ForestTopology, NeighbourRanksAreTheLinkOwnersAndSymmetric) {
    core::Comm world;
    BlockForest const forest(world, GetParam().spec, {}, GetParam().subdomains);
    std::set<int> owners;
    for (Block const& b : forest.blocks())
        for (BlockLink const& l : b.neighbours)
            if (l.owner != world.rank())
                owners.insert(l.owner);
    EXPECT_EQ(std::vector<int>(owners.begin(), owners.end()), forest.neighbourRanks());

    auto const p = static_cast<std::size_t>(world.size());
    std::vector<int> matrix(p * p, 0);
    for (int q : forest.neighbourRanks())
        matrix[static_cast<std::size_t>(world.rank()) * p + static_cast<std::size_t>(q)] = 1;
    world.allReduceInPlace(std::span<int>(matrix), core::ReduceOp::Sum);
    for (std::size_t r = 0; r < p; ++r)
        for (std::size_t q = 0; q < p; ++q)
            EXPECT_EQ(matrix[r * p + q], matrix[q * p + r]) << r << " vs " << q;
}

TEST_P(ForestLeaves, CurveOrderIsHilbertOverRootsThenDepthFirst) {
    core::Comm world;
    BlockForest const forest(world, GetParam().spec);
    auto const all = gatherBlocks(world, forest);
    int const bits = hilbertBitsFor(forest.rootBlocks());
    auto const hilbert = [&](BlockId id) {
        LatticeCell const c = forest.geometry().rootCoord(id.rootIndex());
        return hilbertIndex({static_cast<std::uint32_t>(c[0]), static_cast<std::uint32_t>(c[1]),
                             static_cast<std::uint32_t>(c[2])},
                            bits);
    };
    for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].block.curveIndex, i);
        if (i == 0)
            continue;
        Block const& a = all[i - 1].block;
        Block const& b = all[i].block;
        EXPECT_LE(a.owner, b.owner) << "assignment not contiguous at " << i;
        if (a.id.rootIndex() == b.id.rootIndex()) {
            EXPECT_LT(a.id, b.id) << "not depth-first inside root at " << i;
        } else {
            EXPECT_LT(hilbert(a.id), hilbert(b.id)) << "roots not in Hilbert order at " << i;
        }
    }
}

TEST_P(ForestLeaves, UnitWeightsGiveBlockCountsWithinOneOfTheMean) {
    core::Comm world;
    BlockForest const forest(world, GetParam().spec);
    double const mean = static_cast<double>(forest.globalBlockCount()) / world.size();
    EXPECT_LT(std::abs(static_cast<double>(forest.blocks().size()) - mean), 1.0);
    EXPECT_DOUBLE_EQ(forest.localLoad(), static_cast<double>(forest.blocks().size()));
}

TEST_P(ForestLeaves, WeightedAssignmentIsBalancedContiguousAndRankIndependent) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, randomWeight);

    double localMax = 0.0;
    double sum = 0.0;
    for (Block const& b : forest.blocks()) {
        EXPECT_EQ(b.weight, randomWeight(b.aabb, b.level)) << b.id;
        localMax = std::max(localMax, b.weight);
        sum += b.weight;
    }
    EXPECT_DOUBLE_EQ(sum, forest.localLoad());
    double const total = world.allReduce(forest.localLoad(), core::ReduceOp::Sum);
    double const wmax = world.allReduce(localMax, core::ReduceOp::Max);
    EXPECT_LE(std::abs(forest.localLoad() - total / world.size()), wmax * (1.0 + 1e-12))
        << "load " << forest.localLoad() << ", mean " << total / world.size();

    // Every rank computes the same assignment by itself: compare a digest of it across ranks,
    // and check it against what the ranks actually hold.
    ForestBuilder builder(spec);
    builder.assign(randomWeight, world.size());
    std::uint64_t digest = 1469598103934665603ULL; // FNV-1a
    for (ForestLeaf const& l : builder.leaves())
        for (std::uint64_t v : {l.id.raw(), static_cast<std::uint64_t>(l.owner)})
            digest = (digest ^ v) * 1099511628211ULL;
    auto const digests = world.allGather(static_cast<unsigned long long>(digest));
    for (auto const d : digests)
        EXPECT_EQ(d, digests.front());
    auto const all = gatherBlocks(world, forest);
    ASSERT_EQ(all.size(), builder.leaves().size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].block.id, builder.leaves()[i].id);
        EXPECT_EQ(all[i].heldBy, builder.leaves()[i].owner);
        if (i > 0) {
            EXPECT_LE(all[i - 1].heldBy, all[i].heldBy);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, ForestLeaves, ::testing::ValuesIn(forestCases()),
                         [](auto const& c) { return c.param.name; });
INSTANTIATE_TEST_SUITE_P(Cases, ForestTopology, ::testing::ValuesIn(forestCasesBothWays()),
                         [](auto const& c) { return c.param.name; });
