// Ghost exchange of cell fields: every ghost cell inside the (periodically extended) domain
// gets the value of the interior cell it mirrors, whoever owns it; the reverse exchange adds
// each ghost value to exactly that cell. Checked for 1, 2 and 8 blocks per rank, periodic or
// not on each axis, ghost width 1 and 2, blocks that are their own periodic neighbour (one
// block on an axis), and against an independent count of the ghost copies of each cell.
#include "gravity/field/GhostExchange.hpp"

#include "core/Error.hpp"
#include "tests/gravity/grid/GridTestUtil.hpp"

#include <gtest/gtest.h>

#include <tuple>

using namespace regolith;
using namespace regolith::gravity;

namespace {

/// A value that names a global cell uniquely (exact in a double).
double code(CellLayout const& layout, GlobalCell const& c) {
    auto const& n = layout.globalCells();
    return static_cast<double>(c[0] + n[0] * (c[1] + n[1] * c[2]));
}

using Case = std::tuple<int, std::array<bool, 3>, int>; // blocks per rank, periodic, ghost

class GhostExchangeCase : public ::testing::TestWithParam<Case> {};

TEST_P(GhostExchangeCase, GhostsMirrorTheirInteriorCells) {
    auto const [perRank, periodic, ghost] = GetParam();
    core::Comm world;
    auto const spec = test::cubeSpec(world, perRank, 8, periodic);
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, ghost);
    GhostExchange ex(world, layout);
    CellField f(layout, 2);
    f.fill(-1.0);
    auto const& n = layout.cellsPerBlock();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    auto const& o = layout.origin(b);
                    double const v = code(layout, {o[0] + i, o[1] + j, o[2] + k});
                    f.at(b, i, j, k, 0) = v;
                    f.at(b, i, j, k, 1) = -v - 7.0;
                }
    for (int round = 0; round < 2; ++round) // a plan is reusable
        ex.exchange(f);
    int const g = ghost;
    std::size_t filled = 0;
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = -g; k < n[2] + g; ++k)
            for (int j = -g; j < n[1] + g; ++j)
                for (int i = -g; i < n[0] + g; ++i) {
                    auto const& o = layout.origin(b);
                    auto const w = layout.wrap({o[0] + i, o[1] + j, o[2] + k});
                    double const want = w ? code(layout, *w) : -1.0;
                    ASSERT_EQ(f.at(b, i, j, k, 0), want) << test::describe(spec) << " block " << b
                                                         << " cell " << i << "," << j << "," << k;
                    ASSERT_EQ(f.at(b, i, j, k, 1), w ? -want - 7.0 : -1.0);
                    bool const interior =
                        i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2];
                    if (w && !interior)
                        ++filled;
                }
    EXPECT_EQ(filled, ex.ghostCellsCovered());
}

TEST_P(GhostExchangeCase, ReverseExchangeAddsEachGhostToItsOwner) {
    auto const [perRank, periodic, ghost] = GetParam();
    core::Comm world;
    auto const spec = test::cubeSpec(world, perRank, 8, periodic);
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, ghost);
    GhostExchange ex(world, layout);
    CellField f(layout);
    f.fill(1.0); // interior 1 + one per ghost copy after accumulate
    ex.accumulate(f);
    auto const& n = layout.cellsPerBlock();
    auto const& total = layout.globalCells();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    // Copies of a cell along an axis: itself, one in the ghosts of the block
                    // below if it is within `ghost` of the lower face, one above likewise,
                    // unless that side is a non-periodic domain face.
                    std::array<int, 3> const idx{i, j, k};
                    double copies = 1.0;
                    for (int a = 0; a < 3; ++a) {
                        auto const gc = layout.origin(b)[a] + idx[a];
                        int c = 1;
                        if (idx[a] < ghost && (periodic[a] || gc >= ghost))
                            ++c;
                        if (idx[a] >= n[a] - ghost && (periodic[a] || gc < total[a] - ghost))
                            ++c;
                        copies *= c;
                    }
                    ASSERT_EQ(f.at(b, i, j, k), copies)
                        << test::describe(spec) << " cell " << i << "," << j << "," << k;
                }
}

INSTANTIATE_TEST_SUITE_P(
    Layouts, GhostExchangeCase,
    ::testing::Combine(::testing::Values(1, 2, 8),
                       ::testing::Values(std::array<bool, 3>{false, false, false},
                                         std::array<bool, 3>{true, true, true},
                                         std::array<bool, 3>{true, false, true}),
                       ::testing::Values(1, 2)));

TEST(CellLayout, RefusesBadInput) {
    core::Comm world;
    auto spec = test::cubeSpec(world, 1, 8, {false, false, false});
    domain::BlockForest forest(world, spec);
    auto expectInputError = [&](std::array<int, 3> cells, int ghost, std::string const& key) {
        try {
            CellLayout layout(world, forest, cells, ghost);
            ADD_FAILURE() << "no error for " << key;
        } catch (core::InputError const& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    };
    expectInputError({0, 8, 8}, 1, "domain.cells_per_block");
    expectInputError({1, 1, 1}, 2, "domain.cells_per_block");
    spec.refine.push_back({core::AABB{core::Vec3::Constant(-0.1), core::Vec3::Constant(0.1)}, 1});
    domain::BlockForest refined(world, spec);
    try {
        CellLayout layout(world, refined, {8, 8, 8}, 1);
        ADD_FAILURE() << "a refined forest was accepted";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("domain.refine"), std::string::npos) << e.what();
    }
}

} // namespace
