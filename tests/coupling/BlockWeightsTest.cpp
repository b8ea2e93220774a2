// Block weights of a coupled run (coupling/balance/BlockWeights.hpp): every block weighs
// 1 + its grains + contactWeight x their contacts + cellWeight x its cells, on any rank count, and
// the forest re-assigned with them puts the one crowded block on a rank of its own.
#include "coupling/balance/BlockWeights.hpp"

#include "tests/particles/sync/SyncTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace regolith;
using namespace regolith::particles::synctest;

namespace {

/// 8 x 1 x 1 blocks of edge 1 along x; `crowd` grains in block 0, 10 in every other block.
std::vector<particles::ParticleInit> crowdedRow(int crowd) {
    std::vector<particles::ParticleInit> grains;
    particles::Uid uid = 0;
    for (int b = 0; b < 8; ++b) {
        int const n = b == 0 ? crowd : 10;
        for (int k = 0; k < n; ++k)
            grains.push_back(grain(uid++, Vec3(b + (k + 0.5) / n, 0.5, 0.5), 0.001));
    }
    return grains;
}

int blockIndex(core::AABB const& box) {
    return static_cast<int>(std::lround(box.min.x()));
}

} // namespace

/// The particles on one subdomain per block, or on each rank's blocks merged: the weights are
/// the forest blocks' either way.
class BlockWeightsOn : public ::testing::TestWithParam<domain::Subdomains> {};

TEST_P(BlockWeightsOn, GrainsContactsAndCellsPerBlockOnEveryRank) {
    Comm world;
    auto const spec = forestSpec(Vec3::Zero(), Vec3(8, 1, 1), {8, 1, 1}, allAxes(false));
    domain::BlockForest const forest(world, spec, {}, GetParam());
    particles::LocalParticles local(forest);
    addAll(local, world, crowdedRow(70));
    // The grains of block 3 touch two partners each in the pass counted (entries in their
    // contact histories); every grain keeps an entry of a contact broken before it.
    constexpr std::uint32_t kPass = 2;
    for (particles::BlockParticles& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            bp.particles.history(i).touch(999, kPass - 1);
            if (bp.particles.position(i).x() >= 3.0 && bp.particles.position(i).x() < 4.0)
                for (particles::Uid partner : {1000, 1001})
                    bp.particles.history(i).touch(partner, kPass);
        });
    domain::BlockWeight const grainsOnly =
        coupling::grainAndCellWeights(world, local, local.contactsStamped(kPass), {}, spec);
    domain::BlockWeight const withCells = coupling::grainAndCellWeights(
        world, local, local.contactsStamped(kPass), {{4, 2, 2}, 0.25}, spec);
    double const perContact = coupling::BlockLoadModel::kContactWeight;
    // Every rank answers for every block, not only its own.
    for (int b = 0; b < 8; ++b) {
        core::AABB const box{Vec3(b, 0, 0), Vec3(b + 1, 1, 1)};
        double const grains = b == 0 ? 70.0 : 10.0;
        double const contacts = b == 3 ? 20.0 : 0.0;
        double const load = 1.0 + grains + perContact * contacts;
        EXPECT_DOUBLE_EQ(grainsOnly(box, 0), load) << "block " << b;
        EXPECT_DOUBLE_EQ(withCells(box, 0), load + 0.25 * 16.0) << "block " << b;
    }
    // The direct sum's pairs make a grain weigh more than its contacts; the crowded block
    // (70 grains, 141 units) bounds the imbalance any cut of whole blocks reaches.
    coupling::BlockLoadModel direct;
    direct.grainWeight = coupling::directGravityWeight(140.0, 1.0);
    EXPECT_DOUBLE_EQ(direct.grainWeight, 1.0 + 0.04 * 140.0);
    domain::BlockWeight const withGravity =
        coupling::grainAndCellWeights(world, local, local.contactsStamped(kPass), direct, spec);
    EXPECT_DOUBLE_EQ(withGravity({Vec3(1, 0, 0), Vec3(2, 1, 1)}, 0),
                     1.0 + 10.0 * direct.grainWeight);
    coupling::LoadSpread const spread =
        coupling::loadSpread(world, local, local.contactsStamped(kPass), {});
    double const total = 71.0 + 6 * 11.0 + 11.0 + perContact * 20.0;
    EXPECT_DOUBLE_EQ(spread.blockFloor, std::max(1.0, 71.0 / (total / world.size())));
    EXPECT_GE(spread.imbalance, spread.blockFloor);
    // Counts that miss a copy, or name one more than a block holds, are refused, not read.
    if (!local.blocks().empty()) {
        particles::ContactCounts longer = local.contactsStamped(kPass);
        longer.back().push_back(0);
        EXPECT_THROW(local.requireCountsCover(longer), core::Error);
        EXPECT_THROW(coupling::forEachMasterInLeaf(local, longer, domain::ForestBuilder(spec),
                                                   [](auto&&...) {}),
                     core::Error);
        EXPECT_THROW(local.requireCountsCover({}), core::Error);
    }
    EXPECT_NO_THROW(local.requireCountsCover(local.contactsStamped(kPass)));
}

INSTANTIATE_TEST_SUITE_P(Subdomains, BlockWeightsOn,
                         ::testing::Values(domain::Subdomains::Blocks,
                                           domain::Subdomains::RankBoxes),
                         [](auto const& p) {
                             return p.param == domain::Subdomains::Blocks ? "Blocks" : "Merged";
                         });

TEST(BlockWeights, CrowdedBlockGetsARankOfItsOwn) {
    Comm world;
    auto const spec = forestSpec(Vec3::Zero(), Vec3(8, 1, 1), {8, 1, 1}, allAxes(false));
    domain::BlockForest const uniform(world, spec);
    particles::LocalParticles local(uniform);
    addAll(local, world, crowdedRow(200));
    domain::BlockForest const balanced(
        world, spec,
        coupling::grainAndCellWeights(world, local, local.contactsStamped(0), {}, spec));
    // The load of a rank differs from the mean by less than the heaviest block (the curve
    // cut, domain/SfcPartition.hpp); the crowded block (201 of 278) is alone when P > 1.
    double const total = 201.0 + 7 * 11.0;
    EXPECT_DOUBLE_EQ(world.allReduce(balanced.localLoad(), core::ReduceOp::Sum), total);
    EXPECT_LT(std::abs(balanced.localLoad() - total / world.size()), 201.0);
    bool const holdsCrowd =
        !balanced.blocks().empty() && blockIndex(balanced.blocks().front().aabb) == 0;
    if (holdsCrowd && world.size() > 1) {
        EXPECT_EQ(balanced.blocks().size(), 1u);
    }
    EXPECT_EQ(world.allReduce(static_cast<int>(holdsCrowd), core::ReduceOp::Sum), 1);
}
