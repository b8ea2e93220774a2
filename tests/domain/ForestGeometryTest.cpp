// ForestGeometry: lattice <-> coordinates, block boxes, wrapping at the ulp level.
#include "domain/ForestGeometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace regolith;
using namespace regolith::domain;

namespace {

ForestGeometry geometry(int maxLevel, std::array<bool, 3> periodic = {true, true, false}) {
    return ForestGeometry({core::Vec3(0.1, -0.3, 2.0), core::Vec3(0.7, 0.4, 5.0)}, {3, 2, 5},
                          periodic, maxLevel);
}

} // namespace

TEST(ForestGeometry, PlanesAreExactAtTheEndsAndMonotone) {
    ForestGeometry const g = geometry(3);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(g.coordinate(a, 0), g.domain().min[a]);
        EXPECT_EQ(g.coordinate(a, g.latticeSize(a)), g.domain().max[a]);
        for (LatticeIndex i = 0; i < g.latticeSize(a); ++i)
            EXPECT_LT(g.coordinate(a, i), g.coordinate(a, i + 1));
    }
    // Root faces do not depend on the refinement depth.
    ForestGeometry const coarse = geometry(0);
    for (LatticeIndex i = 0; i <= 3; ++i)
        EXPECT_EQ(coarse.coordinate(0, i), g.coordinate(0, i * 8));
}

TEST(ForestGeometry, BlockBoxesFollowTheirIds) {
    ForestGeometry const g = geometry(2);
    BlockId const root = BlockId::root(g.rootIndex({2, 1, 4}));
    EXPECT_EQ(g.rootCoord(root.rootIndex()), (LatticeCell{2, 1, 4}));
    EXPECT_EQ(g.latticeBox(root), (LatticeBox{{8, 4, 16}, {12, 8, 20}}));
    BlockId const c = root.child(0b101).child(0b010); // upper x and z, then upper y
    EXPECT_EQ(g.latticeBox(c), (LatticeBox{{10, 5, 18}, {11, 6, 19}}));
    EXPECT_EQ(g.blockAt({10, 5, 18}, 2), c);
    EXPECT_EQ(g.blockAt({10, 5, 18}, 1), c.parent());
    core::AABB const box = g.box(c);
    EXPECT_EQ(box.min[0], g.coordinate(0, 10));
    EXPECT_EQ(box.max[2], g.coordinate(2, 19));
}

TEST(ForestGeometry, LocateUsesHalfOpenCellsAndPeriodicImages) {
    ForestGeometry const g = geometry(2);
    for (LatticeIndex i = 0; i < g.latticeSize(0); ++i) { // every plane belongs to the cell above
        auto const loc = g.locate({g.coordinate(0, i), 0.0, 3.0});
        ASSERT_TRUE(loc.has_value());
        EXPECT_EQ(loc->cell[0], i);
        auto const below = g.locate({std::nextafter(g.coordinate(0, i), -1.0), 0.0, 3.0});
        ASSERT_TRUE(below.has_value());
        EXPECT_EQ(below->cell[0], i == 0 ? g.latticeSize(0) - 1 : i - 1);
        EXPECT_EQ(below->image[0], i == 0 ? -1 : 0);
    }
    // Outside the domain on the non-periodic z axis: nowhere.
    EXPECT_FALSE(g.locate({0.2, 0.0, 5.0}).has_value());
    EXPECT_FALSE(g.locate({0.2, 0.0, std::numeric_limits<double>::quiet_NaN()}).has_value());
    // Two periods up on x, one down on y.
    auto const far = g.locate({0.1 + 2 * 0.6 + 0.01, -0.3 - 0.7 + 0.01, 3.0});
    ASSERT_TRUE(far.has_value());
    EXPECT_EQ(far->image, (PeriodicImage{2, -1, 0}));
    EXPECT_EQ(far->cell[0], 0);
    EXPECT_EQ(far->cell[1], 0);
}

TEST(ForestGeometry, WrapNeverReturnsTheUpperFace) {
    ForestGeometry const g({core::Vec3(0, 0, 0), core::Vec3(1, 1, 1)}, {1, 1, 1},
                           {true, true, true}, 0);
    core::Vec3 const w = g.wrap({-1e-17, 1.0, 2.0});
    EXPECT_LT(w[0], 1.0); // 1 - 1e-17 rounds to 1 in double: must be clamped below
    EXPECT_GE(w[0], 0.0);
    EXPECT_EQ(w[1], 0.0);
    EXPECT_EQ(w[2], 0.0);
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> tiny(-1e-15, 1e-15);
    for (int i = 0; i < 1000; ++i) {
        core::Vec3 const p(tiny(rng), 1.0 + tiny(rng), -3.0 + tiny(rng));
        core::Vec3 const q = g.wrap(p);
        EXPECT_TRUE((q.array() >= 0.0).all() && (q.array() < 1.0).all()) << p.transpose();
        EXPECT_TRUE(g.insideDomain(p));
    }
    EXPECT_EQ(g.shift({1, 0, -2}), core::Vec3(-1.0, 0.0, 2.0));
}
