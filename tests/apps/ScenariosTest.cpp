// The reference scenes' layouts over the ranks (apps/scenarios): rank grids and the keys the
// expansions write.
#include "apps/scenarios/Scenarios.hpp"

#include "apps/scenarios/RankGrid.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

namespace regolith::apps {
namespace {

using Vec = std::array<double, 3>;
using Counts = std::array<std::int64_t, 3>;

TEST(RankGrid, MostCubicFactorisation) {
    EXPECT_EQ(rankGrid(1), (std::array<int, 3>{1, 1, 1}));
    EXPECT_EQ(rankGrid(2), (std::array<int, 3>{2, 1, 1}));
    EXPECT_EQ(rankGrid(4), (std::array<int, 3>{2, 2, 1}));
    EXPECT_EQ(rankGrid(8), (std::array<int, 3>{2, 2, 2}));
    EXPECT_EQ(rankGrid(12), (std::array<int, 3>{3, 2, 2}));
    EXPECT_EQ(rankGrid(27), (std::array<int, 3>{3, 3, 3}));
    EXPECT_EQ(rankGrid(7), (std::array<int, 3>{7, 1, 1}));
    EXPECT_EQ(rankGrid(8, 2), (std::array<int, 3>{4, 2, 1}));
    EXPECT_EQ(rankGrid(16, 2), (std::array<int, 3>{4, 4, 1}));
    EXPECT_THROW((void)rankGrid(0), core::Error);
}

core::ConfigTable scene(std::string const& text) {
    return core::ConfigTable::fromString(text, "test.toml");
}

TEST(Scenarios, GranularGasWeakScalingGrowsWithTheRanks) {
    auto s = scene("[granular_gas]\nper_rank = [10.0, 20.0, 30.0]\nblocks_per_rank = [1, 2, 1]\n"
                   "[domain]\nmin = [1.0, 0.0, 0.0]\n");
    expandScenarios(s, 12);
    EXPECT_EQ(s.table("domain").get<Vec>("max"), (Vec{31.0, 40.0, 60.0}));
    EXPECT_EQ(s.table("domain").get<Counts>("blocks"), (Counts{3, 4, 2}));
}

TEST(Scenarios, GranularGasStrongScalingKeepsTheBox) {
    auto s = scene("[granular_gas]\nscaling = \"strong\"\nbox = [40.0, 40.0, 40.0]\n"
                   "[domain]\nmin = [0.0, 0.0, 0.0]\n");
    expandScenarios(s, 8);
    EXPECT_EQ(s.table("domain").get<Vec>("max"), (Vec{40.0, 40.0, 40.0}));
    EXPECT_EQ(s.table("domain").get<Counts>("blocks"), (Counts{2, 2, 2}));
}

TEST(Scenarios, RefusesWhatItCannotLayOut) {
    auto owned = scene("[granular_gas]\n[domain]\nmax = [1.0, 1.0, 1.0]\n");
    EXPECT_THROW(expandScenarios(owned, 1), core::InputError);
    auto noBox = scene("[granular_gas]\nscaling = \"strong\"\n[domain]\n");
    EXPECT_THROW(expandScenarios(noBox, 1), core::InputError);
    auto badBlocks = scene("[granular_gas]\nblocks_per_rank = [1, 0, 1]\n[domain]\n");
    EXPECT_THROW(expandScenarios(badBlocks, 1), core::InputError);
    auto badRadius = scene("[bidisperse]\nedge = 20.0\nlarge_radius = 10.0\n[domain]\n"
                           "[[particles]]\nkind = \"list\"\n");
    EXPECT_THROW(expandScenarios(badRadius, 1), core::InputError);
    // The messages name the keys of this scenario (not another's, not none).
    auto const message = [](std::string const& text) {
        auto s = scene(text);
        try {
            expandScenarios(s, 1);
        } catch (core::InputError const& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message("[bidisperse]\n[domain]\nblocks = [1, 1, 1]\n"),
              "test.toml:3: domain.blocks: is set by the [bidisperse] scenario; change "
              "bidisperse.building_blocks, bidisperse.blocks_per_building_block or "
              "bidisperse.edge instead");
    EXPECT_EQ(message("[granular_gas]\n[bidisperse]\n[domain]\n"),
              "test.toml:2: [bidisperse]: a scene takes one scenario section, and "
              "[granular_gas] is one already");
    EXPECT_EQ(message("[granular_gas]\nbox = [4.0, 4.0, 4.0]\n[domain]\n"),
              "test.toml:2: granular_gas.box: applies only with scaling = \"strong\" (weak "
              "scaling takes the extent from per_rank and the rank count)");
}

TEST(Scenarios, DenseRampTiltsGravityAndLiftsTheTopWall) {
    auto s = scene("[dense_ramp]\n[domain]\nmin = [0.0, 0.0, 2.0]\n"
                   "[[walls]]\npoint = [0.0, 0.0, 2.0]\n[[walls]]\npoint = [0.0, 0.0, 0.0]\n");
    expandScenarios(s, 4);
    auto const g = s.table("gravity").get<Vec>("external");
    EXPECT_NEAR(g[0], 0.5, 1e-15);
    EXPECT_NEAR(g[2], -std::sqrt(3.0) / 2.0, 1e-15);
    auto const max = s.table("domain").get<Vec>("max");
    EXPECT_EQ(max[0], 40.0); // 2-D rank grid {2, 2, 1}
    EXPECT_NEAR(max[1], 20.0 * std::sqrt(3.0), 1e-12);
    EXPECT_EQ(max[2], 10.0);
    EXPECT_EQ(s.tableArray("walls")[1].get<Vec>("point"), (Vec{0.0, 0.0, 10.0}));
}

TEST(Scenarios, BidisperseHasOneLargeSphereAtTheCentreOfEveryBuildingBlock) {
    auto s = scene("[bidisperse]\nbuilding_blocks = [2, 1, 1]\nedge = 80.0\nlarge_radius = 30.0\n"
                   "[domain]\n[[particles]]\nkind = \"list\"\n");
    expandScenarios(s, 1);
    EXPECT_EQ(s.table("domain").get<Vec>("max"), (Vec{160.0, 80.0, 80.0}));
    EXPECT_EQ(s.table("domain").get<Counts>("blocks"), (Counts{8, 4, 4}));
    auto const entry = s.tableArray("particles")[0];
    EXPECT_EQ(entry.get<std::vector<double>>("radius"), (std::vector<double>{30.0, 30.0}));
    EXPECT_EQ(entry.get<std::vector<core::Vec3>>("position"),
              (std::vector<core::Vec3>{{40.0, 40.0, 40.0}, {120.0, 40.0, 40.0}}));
}

} // namespace
} // namespace regolith::apps
