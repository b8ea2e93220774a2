// The gravity-only halo of P3M finds every pair within the cut-off: for random grains over
// the whole domain (many near block faces, corners and periodic faces), each local grain's
// neighbours within the cut-off among the local grains plus the halo equal those of a brute
// force over all grains and all periodic images. Cut-offs below and above the block edge, so
// that blocks beyond the face neighbours are searched too; 1, 2, 4 ranks.
#include "coupling/gravity/ShortRangeHalo.hpp"

#include "gravity/field/CellLayout.hpp"
#include "tests/coupling/CouplingTestUtil.hpp"

#include <gtest/gtest.h>

#include <random>
#include <tuple>

using namespace regolith;

namespace {

class ShortRangeHaloTest : public ::testing::TestWithParam<std::tuple<bool, double>> {};

TEST_P(ShortRangeHaloTest, FindsEveryPairWithinTheCutoff) {
    auto const& world = coupling::test::world();
    bool const periodic = std::get<0>(GetParam());
    double const cutoff = std::get<1>(GetParam());
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Constant(-8.0), core::Vec3::Constant(8.0)};
    spec.rootBlocks = {4, 2, 2}; // blocks of 4 x 8 x 8
    spec.periodic = {periodic, periodic, periodic};
    spec.cellsPerBlock = {4, 8, 8};
    domain::BlockForest const forest(world, spec);
    gravity::CellLayout const layout(world, forest, spec.cellsPerBlock, 1);
    coupling::ShortRangeHalo halo(world, forest, layout, cutoff);

    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-8.0, 8.0);
    std::size_t const n = 600;
    std::vector<core::Vec3> all(n);
    for (auto& x : all)
        x = {u(rng), u(rng), u(rng)};
    std::vector<core::Vec3> local;
    std::vector<double> mass;
    std::vector<std::size_t> localIndex;
    for (std::size_t k = 0; k < n; ++k)
        if (forest.localBlockContaining(all[k]) != nullptr) {
            local.push_back(all[k]);
            mass.push_back(static_cast<double>(k)); // the mass carries the index back
            localIndex.push_back(k);
        }
    halo.gather(local, mass);

    std::vector<double> found(n, 0.0), expected(n, 0.0);
    int const reach = periodic ? 1 : 0;
    for (std::size_t i = 0; i < local.size(); ++i) {
        for (std::size_t j = 0; j < local.size(); ++j)
            if (j != i && (local[j] - local[i]).norm() < cutoff)
                found[localIndex[i]] += 1.0;
        for (core::Vec3 const& h : halo.position())
            if ((h - local[i]).norm() < cutoff)
                found[localIndex[i]] += 1.0;
        for (std::size_t j = 0; j < n; ++j)
            for (int sz = -reach; sz <= reach; ++sz)
                for (int sy = -reach; sy <= reach; ++sy)
                    for (int sx = -reach; sx <= reach; ++sx) {
                        if (j == localIndex[i] && sx == 0 && sy == 0 && sz == 0)
                            continue;
                        core::Vec3 const image = all[j] + 16.0 * core::Vec3(sx, sy, sz);
                        if ((image - local[i]).norm() < cutoff)
                            expected[localIndex[i]] += 1.0;
                    }
    }
    // Every halo grain is some grain's image within the cut-off of a local block.
    for (std::size_t k = 0; k < halo.mass().size(); ++k) {
        double const idx = halo.mass()[k];
        EXPECT_EQ(idx, std::floor(idx));
        EXPECT_GE(idx, 0.0);
        EXPECT_LT(idx, static_cast<double>(n));
    }
    world.allReduceInPlace(std::span<double>(found), core::ReduceOp::Sum);
    world.allReduceInPlace(std::span<double>(expected), core::ReduceOp::Sum);
    double pairs = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        EXPECT_EQ(found[k], expected[k]) << "grain " << k;
        pairs += expected[k];
    }
    EXPECT_GT(pairs, static_cast<double>(n)); // the test means something: many pairs
}

INSTANTIATE_TEST_SUITE_P(Layouts, ShortRangeHaloTest,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(1.5, 5.0)));

} // namespace
