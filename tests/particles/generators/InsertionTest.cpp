// Grain insertion ([[insert]]): a batch lies inside its region, overlaps nothing, does not
// depend on the order of the grains around it, and stops where the region is full.
#include "particles/generators/GrainInsertion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace regolith::particles;
using regolith::core::AABB;
using regolith::core::Vec3;

namespace {

InsertSpec boxSpec() {
    InsertSpec s;
    s.region.box = AABB{Vec3(0, 0, 0), Vec3(4, 4, 4)};
    s.count = 100;
    s.radiusMin = 0.2;
    s.radiusMax = 0.3;
    s.density = 2.0;
    s.velocity = Vec3(0, 0, -1);
    s.seed = 9;
    return s;
}

void expectNoOverlap(std::vector<GrainInit> const& g, std::vector<PlacedSphere> const& near) {
    for (std::size_t i = 0; i < g.size(); ++i) {
        for (std::size_t j = i + 1; j < g.size(); ++j)
            EXPECT_GE((g[i].position - g[j].position).norm(), g[i].radius + g[j].radius);
        for (PlacedSphere const& s : near)
            EXPECT_GE((g[i].position - s.centre).norm(), g[i].radius + s.radius);
    }
}

} // namespace

TEST(Insertion, BatchInsideTheRegionWithoutOverlap) {
    InsertSpec const spec = boxSpec();
    std::vector<PlacedSphere> near{{Vec3(2, 2, 2), 1.0}, {Vec3(0.5, 3.5, 1), 0.4}};
    WallList walls;
    walls.add(Vec3(0, 0, 1), Vec3::UnitZ()); // a floor through the region
    auto const g = placeBatch(spec, 1, 2, 10, 60, near, walls, {});
    ASSERT_EQ(g.size(), 60u);
    for (std::size_t k = 0; k < g.size(); ++k) {
        EXPECT_EQ(g[k].uid, insertedUid(1, 10 + k));
        EXPECT_EQ(insertEntryOf(g[k].uid), 1);
        EXPECT_GE(g[k].radius, 0.2);
        EXPECT_LE(g[k].radius, 0.3);
        EXPECT_GE(g[k].position.z() - g[k].radius, 1.0); // above the floor
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(g[k].position[a] - g[k].radius, 0.0);
            EXPECT_LE(g[k].position[a] + g[k].radius, 4.0);
        }
        EXPECT_EQ(g[k].velocity, Vec3(0, 0, -1));
        EXPECT_DOUBLE_EQ(g[k].mass, sphereMass(g[k].radius, 2.0));
    }
    expectNoOverlap(g, near);
    EXPECT_EQ(insertEntryOf(makeUid(0, 5)), static_cast<long>(kFirstReservedRank - 1));
}

TEST(Insertion, SameGrainsWhateverTheOrderAroundThem) {
    InsertSpec const spec = boxSpec();
    std::vector<PlacedSphere> near;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    for (int k = 0; k < 40; ++k)
        near.push_back({Vec3(u(rng), u(rng), u(rng)), 0.25});
    auto const a = placeBatch(spec, 0, 1, 0, 50, near, WallList{}, {});
    std::reverse(near.begin(), near.end());
    auto const b = placeBatch(spec, 0, 1, 0, 50, near, WallList{}, {});
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].position, b[k].position); // bit for bit
        EXPECT_EQ(a[k].radius, b[k].radius);
    }
    expectNoOverlap(a, near);
    // Another batch draws other places for the same grains.
    auto const c = placeBatch(spec, 0, 2, 0, 1, near, WallList{}, {});
    ASSERT_EQ(c.size(), 1u);
    EXPECT_NE(c[0].position, a[0].position);
}

TEST(Insertion, CylinderRegionAndAFullRegion) {
    InsertSpec spec = boxSpec();
    spec.region.shape = InsertRegion::Shape::Cylinder;
    spec.region.base = Vec3(1, 1, 1);
    spec.region.axis = Vec3::UnitX();
    spec.region.radius = 1.0;
    spec.region.length = 2.0;
    AABB const bounds = spec.region.bounds();
    EXPECT_LT((bounds.min - Vec3(1, 0, 0)).norm(), 1e-15);
    EXPECT_LT((bounds.max - Vec3(3, 2, 2)).norm(), 1e-15);
    auto const g = placeBatch(spec, 0, 1, 0, 20, {}, WallList{}, {});
    ASSERT_EQ(g.size(), 20u);
    for (GrainInit const& x : g) {
        Vec3 const d = x.position - spec.region.base;
        EXPECT_LE(std::hypot(d.y(), d.z()) + x.radius, 1.0 + 1e-12);
        EXPECT_GE(d.x() - x.radius, -1e-12);
        EXPECT_LE(d.x() + x.radius, 2.0 + 1e-12);
    }
    expectNoOverlap(g, {});
    // A region that holds one grain: the second waits (and the rest after it).
    spec.region.radius = 0.35;
    spec.region.length = 0.7;
    spec.radiusMin = spec.radiusMax = 0.3;
    EXPECT_EQ(placeBatch(spec, 0, 1, 0, 5, {}, WallList{}, {}).size(), 1u);
}

TEST(Insertion, PeriodicImagesCount) {
    InsertSpec spec = boxSpec();
    spec.region.box = AABB{Vec3(0, 0, 0), Vec3(1, 1, 1)};
    spec.radiusMin = spec.radiusMax = 0.3;
    // A grain just across the periodic x face (period 10) at x = 9.9 fills the region's
    // low-x corner through its image at -0.1.
    std::vector<PlacedSphere> const near{{Vec3(9.9, 0.5, 0.5), 0.45}};
    auto const g = placeBatch(spec, 0, 1, 0, 1, near, WallList{}, {10.0, 0.0, 0.0});
    ASSERT_EQ(g.size(), 1u);
    EXPECT_GE((g[0].position - Vec3(-0.1, 0.5, 0.5)).norm(), 0.75);
}
