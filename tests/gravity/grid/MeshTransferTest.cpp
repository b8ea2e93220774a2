// Deposition and interpolation: mass conserved to round-off for grains straddling block
// faces, edges, corners and periodic boundaries, and for grains larger than a block; linear
// fields interpolated exactly (both kernels reproduce linear functions); grains outside the
// domain refused on every rank.
#include "gravity/transfer/MeshTransfer.hpp"

#include "core/Error.hpp"
#include "tests/gravity/grid/GridTestUtil.hpp"

#include <gtest/gtest.h>

#include <random>
#include <tuple>

using namespace regolith;
using namespace regolith::gravity;

namespace {

struct GrainSet {
    std::vector<core::Vec3> position;
    std::vector<double> radius;
    std::vector<double> mass;
    [[nodiscard]] Grains view() const { return {position, radius, mass}; }
};

/// Grains that this rank contributes (grain g goes to rank g % size): on block faces, edges
/// and corners (coordinates on the block lattice, which for 4 blocks per axis in [-1, 1] are
/// multiples of 0.5), on the domain faces when periodic, and random; radii from 0 to 0.6
/// (larger than a block of 0.5). Returns the total mass over all ranks.
double makeGrains(core::Comm const& comm, bool periodic, GrainSet& out) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double const lim = periodic ? 1.0 : 0.2; // keep kernels inside a non-periodic domain
    std::vector<double> lattice{-0.5, 0.0, 0.5};
    if (periodic)
        lattice.push_back(-1.0);
    double total = 0.0;
    for (int g = 0; g < 200; ++g) {
        core::Vec3 p;
        for (int a = 0; a < 3; ++a) {
            double const pick = unit(rng);
            if (pick < 0.5) // on a block plane (face, edge or corner when several axes hit)
                p[a] = lattice[static_cast<std::size_t>(unit(rng) *
                                                        static_cast<double>(lattice.size()))];
            else
                p[a] = (2.0 * unit(rng) - 1.0) * (periodic ? 1.0 : 0.7);
            if (!periodic)
                p[a] = std::clamp(p[a], -0.7, 0.7);
        }
        double r = unit(rng) < 0.2 ? 0.0 : 0.6 * unit(rng) * unit(rng);
        if (!periodic)
            r = std::min(r, lim);
        double const m = 0.5 + unit(rng);
        total += m;
        if (g % comm.size() == comm.rank()) {
            out.position.push_back(p);
            out.radius.push_back(r);
            out.mass.push_back(m);
        }
    }
    return total;
}

using Case = std::tuple<int, bool, Assignment>; // blocks per rank, periodic, kernel

class Deposition : public ::testing::TestWithParam<Case> {};

TEST_P(Deposition, ConservesMassToRoundOff) {
    auto const [perRank, periodic, scheme] = GetParam();
    core::Comm world;
    auto const spec = test::cubeSpec(world, perRank, 16, {periodic, periodic, periodic});
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, 1);
    MeshTransfer transfer(world, layout, scheme);
    GrainSet grains;
    double const total = makeGrains(world, periodic, grains);
    CellField rho(layout);
    transfer.deposit(grains.view(), rho);
    double const mass =
        world.allReduce(rho.localInteriorSum() * layout.cellVolume(), core::ReduceOp::Sum);
    // Round-off: ~1e-16 per operation over a few thousand additions per grain.
    EXPECT_NEAR(mass, total, 1e-12 * total) << test::describe(spec);
}

TEST_P(Deposition, LargeGrainSpreadsOverManyBlocks) {
    auto const [perRank, periodic, scheme] = GetParam();
    core::Comm world;
    auto const spec = test::cubeSpec(world, perRank, 16, {periodic, periodic, periodic});
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, 1);
    MeshTransfer transfer(world, layout, scheme);
    GrainSet g;
    if (world.rank() == world.size() - 1) { // one big grain, deposited by the last rank
        g.position.push_back(core::Vec3{0.05, -0.02, 0.01});
        g.radius.push_back(0.7);
        g.mass.push_back(3.0);
    }
    CellField rho(layout);
    transfer.deposit(g.view(), rho);
    double const mass =
        world.allReduce(rho.localInteriorSum() * layout.cellVolume(), core::ReduceOp::Sum);
    EXPECT_NEAR(mass, 3.0, 1e-13);
    // The ball's volume fraction of the cells: a cell near the centre holds the mean density.
    // Blocks holding some of its mass (ghosts stay zero, so a block's array sum is its own).
    int blocksHit = 0;
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        double sum = 0.0;
        for (double v : rho.block(b))
            sum += v;
        blocksHit += sum > 0.0 ? 1 : 0;
    }
    int const hit = world.allReduce(blocksHit, core::ReduceOp::Sum);
    auto const blocks = static_cast<int>(forest.globalBlockCount());
    EXPECT_GE(hit, std::min(blocks, 8)) << test::describe(spec);
    double const volume = 4.0 / 3.0 * M_PI * 0.7 * 0.7 * 0.7;
    double const mean = 3.0 / volume;
    auto const centre = layout.owner({8, 7, 8});
    ASSERT_TRUE(centre);
    if (centre->localBlock >= 0) {
        double const v = rho.block(
            static_cast<std::size_t>(centre->localBlock))[layout.padOfInterior(centre->interior)];
        EXPECT_NEAR(v, mean, 0.05 * mean); // the ball is sampled at spacing <= h
    }
}

TEST_P(Deposition, InterpolatesLinearFieldsExactly) {
    auto const [perRank, periodic, scheme] = GetParam();
    if (periodic)
        GTEST_SKIP() << "a linear field is not periodic";
    core::Comm world;
    auto const spec = test::cubeSpec(world, perRank, 16, {false, false, false});
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, 1);
    MeshTransfer transfer(world, layout, scheme);
    CellField f(layout, 2);
    auto const& n = layout.cellsPerBlock();
    auto linear = [](core::Vec3 const& x) { return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2]; };
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    auto const& o = layout.origin(b);
                    core::Vec3 const x = layout.centre({o[0] + i, o[1] + j, o[2] + k});
                    f.at(b, i, j, k, 0) = linear(x);
                    f.at(b, i, j, k, 1) = 7.0;
                }
    GrainSet g;
    double const total = makeGrains(world, false, g);
    (void)total;
    std::vector<double> out(g.position.size() * 2);
    transfer.interpolate(g.view(), f, out);
    for (std::size_t i = 0; i < g.position.size(); ++i) {
        EXPECT_NEAR(out[2 * i], linear(g.position[i]), 1e-12) << "grain " << i;
        EXPECT_NEAR(out[2 * i + 1], 7.0, 1e-12);
    }
}

INSTANTIATE_TEST_SUITE_P(Layouts, Deposition,
                         ::testing::Combine(::testing::Values(1, 2, 8),
                                            ::testing::Values(false, true),
                                            ::testing::Values(Assignment::Cic, Assignment::Tsc)));

TEST(Deposition, MassOutsideTheDomainIsRefusedOnEveryRank) {
    core::Comm world;
    auto const spec = test::cubeSpec(world, 2, 16, {false, false, true});
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, 1);
    MeshTransfer transfer(world, layout, Assignment::Tsc);
    for (double x : {1.5, 0.99}) { // centre outside; kernel reaching past the face
        GrainSet g;
        if (world.rank() == 0) {
            g.position.push_back(core::Vec3{x, 0.0, 0.0});
            g.radius.push_back(0.0);
            g.mass.push_back(1.0);
        }
        CellField rho(layout);
        try {
            transfer.deposit(g.view(), rho);
            ADD_FAILURE() << "no error for a grain at x = " << x;
        } catch (core::InputError const& e) {
            EXPECT_NE(std::string(e.what()).find("outside the domain"), std::string::npos)
                << e.what();
        }
    }
    // Across a periodic face the same grain is fine.
    GrainSet g;
    if (world.rank() == 0) {
        g.position.push_back(core::Vec3{0.0, 0.0, 0.999});
        g.radius.push_back(0.0);
        g.mass.push_back(1.0);
    }
    CellField rho(layout);
    EXPECT_NO_THROW(transfer.deposit(g.view(), rho));
}

} // namespace
