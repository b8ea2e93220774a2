// Point location and sphere / box overlap queries against a brute-force reference over all
// blocks of all ranks and all periodic images, on a few thousand random queries per case.
// Random streams are seeded per point or per block (by curve index), so the queries do not
// depend on the number of ranks.
#include "domain/BlockForest.hpp"
#include "tests/domain/GlobalForest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace regolith;
using namespace regolith::domain;
using namespace regolith::domain::test;

namespace {

class ForestQuery : public ::testing::TestWithParam<ForestCase> {};

constexpr int kQueries = 3000; ///< per test and case, spread over the blocks

core::Vec3 uniformIn(std::mt19937_64& rng, core::AABB const& box) {
    core::Vec3 p;
    for (int a = 0; a < 3; ++a)
        p[a] = std::uniform_real_distribution<double>(box.min[a], box.max[a])(rng);
    return p;
}

/// The box grown by margin[a] on both sides of each axis.
core::AABB grown(core::AABB const& b, core::Vec3 const& margin) {
    return {b.min - margin, b.max + margin};
}

/// Whether any block of any rank has a neighbour link. Collective.
bool anyLinks(core::Comm const& world, BlockForest const& forest) {
    bool mine = false;
    for (Block const& b : forest.blocks())
        mine = mine || !b.neighbours.empty();
    return !world.allTrue(!mine);
}

int queriesPerBlock(std::size_t blocks) {
    return std::max(4, kQueries / static_cast<int>(blocks));
}

/// Every (block, image) for which `hit(image box)` holds, except `self` with image 0.
template <class Hit>
std::vector<LinkKey> bruteForce(std::vector<GlobalBlock> const& all, ForestSpec const& spec,
                                BlockId self, Hit hit) {
    std::vector<LinkKey> out;
    for (PeriodicImage const& o : candidateImages(spec.periodic))
        for (GlobalBlock const& g : all) {
            if (g.block.id == self && o == PeriodicImage{0, 0, 0})
                continue;
            if (hit(g.block.aabb.shifted(translation(spec.domain, o))))
                out.push_back(LinkKey{g.block.id.raw(), o});
        }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST_P(ForestQuery, LocalBlockContainingAgreesWithBruteForce) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);

    std::vector<core::Vec3> points;
    std::mt19937_64 rng(20240601);
    for (int i = 0; i < kQueries; ++i)
        points.push_back(uniformIn(rng, spec.domain));
    for (GlobalBlock const& g : all) // lower corners lie on shared faces: half-open decides
        points.push_back(g.block.aabb.min);

    long found = 0;
    for (core::Vec3 const& p : points) {
        std::vector<GlobalBlock const*> holders;
        for (GlobalBlock const& g : all)
            if (g.block.aabb.contains(p))
                holders.push_back(&g);
        EXPECT_EQ(holders.size(), 1U) << p.transpose();
        Block const* local = forest.localBlockContaining(p);
        if (local != nullptr)
            ++found;
        if (holders.size() != 1)
            continue;
        if (holders.front()->heldBy == world.rank()) {
            EXPECT_TRUE(local != nullptr && local->id == holders.front()->block.id)
                << p.transpose();
        } else {
            EXPECT_EQ(local, nullptr) << p.transpose();
        }
    }
    EXPECT_EQ(world.allReduce(found, core::ReduceOp::Sum), static_cast<long>(points.size()));
    // Upper faces of the domain and points outside belong to no block.
    EXPECT_EQ(forest.localBlockContaining(spec.domain.max), nullptr);
    EXPECT_EQ(forest.localBlockContaining(spec.domain.min - spec.domain.extent()), nullptr);
}

TEST_P(ForestQuery, BlockContainingFromLocalBlockAgreesWithBruteForce) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);
    // Points within 0.9 finest edges of the block lie in the block or a touching image.
    core::Vec3 const margin = 0.9 * finestEdge(all);
    int const perBlock = queriesPerBlock(all.size());

    long outside = 0;
    for (Block const& b : forest.blocks()) {
        std::mt19937_64 rng(7 + b.curveIndex);
        for (int k = 0; k < perBlock; ++k) {
            core::Vec3 const p = uniformIn(rng, grown(b.aabb, margin));
            std::vector<LinkKey> ref;
            for (PeriodicImage const& o : candidateImages(spec.periodic))
                for (GlobalBlock const& g : all)
                    if (g.block.aabb.shifted(translation(spec.domain, o)).contains(p))
                        ref.push_back(LinkKey{g.block.id.raw(), o});
            auto const got = forest.blockContaining(b, p);
            if (ref.empty()) { // outside the domain on a non-periodic axis
                ++outside;
                EXPECT_FALSE(got.has_value()) << b.id << " " << p.transpose();
                continue;
            }
            EXPECT_EQ(ref.size(), 1U) << p.transpose();
            if (!got.has_value()) {
                ADD_FAILURE() << "no block found from " << b.id << " for " << p.transpose();
                continue;
            }
            EXPECT_EQ((LinkKey{got->id.raw(), got->image}), ref.front()) << p.transpose();
            EXPECT_EQ(got->shift, -translation(spec.domain, got->image));
            EXPECT_TRUE(got->aabb.contains(p + got->shift)) << p.transpose();
        }
    }
    bool const anyNonPeriodic = !(spec.periodic[0] && spec.periodic[1] && spec.periodic[2]);
    long const totalOutside = world.allReduce(outside, core::ReduceOp::Sum);
    EXPECT_EQ(totalOutside > 0, anyNonPeriodic) << "the margin should leave the domain";
}

TEST_P(ForestQuery, SphereOverlapAgreesWithBruteForce) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);
    core::Vec3 const h = finestEdge(all);
    int const perBlock = queriesPerBlock(all.size());

    long hits = 0;
    for (Block const& b : forest.blocks()) {
        std::mt19937_64 rng(11 + b.curveIndex);
        // margin + radius < finest edge per axis: every image reached touches the block.
        for (int k = 0; k < perBlock; ++k) {
            core::Vec3 const c = uniformIn(rng, grown(b.aabb, 0.45 * h));
            double const r = std::uniform_real_distribution<double>(0.0, 0.5 * h.minCoeff())(rng);
            auto const ref = bruteForce(
                all, spec, b.id, [&](core::AABB const& box) { return box.intersectsSphere(c, r); });
            EXPECT_EQ(keysOf(forest.linksOverlappingSphere(b, c, r)), ref)
                << b.id << " c = " << c.transpose() << " r = " << r;
            hits += static_cast<long>(ref.size());
        }
    }
    // A forest merged into one box per rank may have no links (one rank, no periodic axis).
    EXPECT_EQ(world.allReduce(hits, core::ReduceOp::Sum) > 0, anyLinks(world, forest));
}

TEST_P(ForestQuery, BoxOverlapAgreesWithBruteForce) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    auto const all = gatherBlocks(world, forest);
    core::Vec3 const h = finestEdge(all);
    int const perBlock = queriesPerBlock(all.size());

    long hits = 0;
    for (Block const& b : forest.blocks()) {
        // The block itself (grown by far less than any gap) touches every linked image.
        EXPECT_EQ(forest.linksOverlappingBox(b, grown(b.aabb, 1e-9 * h)).size(),
                  b.neighbours.size());
        std::mt19937_64 rng(13 + b.curveIndex);
        for (int k = 0; k < perBlock; ++k) {
            core::Vec3 const c = uniformIn(rng, grown(b.aabb, 0.3 * h));
            core::Vec3 half;
            for (int a = 0; a < 3; ++a)
                half[a] = std::uniform_real_distribution<double>(0.0, 0.3 * h[a])(rng);
            core::AABB const box{c - half, c + half};
            auto const ref = bruteForce(all, spec, b.id, [&](core::AABB const& image) {
                return image.intersectsClosed(box);
            });
            EXPECT_EQ(keysOf(forest.linksOverlappingBox(b, box)), ref)
                << b.id << " box " << box.min.transpose() << " - " << box.max.transpose();
            hits += static_cast<long>(ref.size());
        }
    }
    // A forest merged into one box per rank may have no links (one rank, no periodic axis).
    EXPECT_EQ(world.allReduce(hits, core::ReduceOp::Sum) > 0, anyLinks(world, forest));
}

TEST_P(ForestQuery, WrapAndInsideDomainAgreeWithReference) {
    core::Comm world;
    ForestSpec const& spec = GetParam().spec;
    BlockForest const forest(world, spec, {}, GetParam().subdomains);
    core::Vec3 const l = spec.domain.extent();
    core::AABB const wide{spec.domain.min - 2.0 * l, spec.domain.max + 2.0 * l};
    std::mt19937_64 rng(17);
    for (int i = 0; i < kQueries; ++i) {
        core::Vec3 const p = uniformIn(rng, wide);
        core::Vec3 const w = forest.wrap(p);
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
            bool const in = p[a] >= spec.domain.min[a] && p[a] < spec.domain.max[a];
            if (!spec.periodic[a]) {
                EXPECT_EQ(w[a], p[a]);
                inside = inside && in;
                continue;
            }
            EXPECT_GE(w[a], spec.domain.min[a]);
            EXPECT_LT(w[a], spec.domain.max[a]);
            double const periods = (p[a] - w[a]) / l[a];
            EXPECT_NEAR(periods, std::round(periods), 1e-9) << p.transpose();
            if (in) {
                EXPECT_EQ(w[a], p[a]);
            }
        }
        EXPECT_EQ(forest.insideDomain(p), inside) << p.transpose();
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, ForestQuery, ::testing::ValuesIn(forestCasesBothWays()),
                         [](auto const& c) { return c.param.name; });
