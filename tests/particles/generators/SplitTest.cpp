// Rank independence: generating a scene box by box (1, 2, 8, 12 boxes tiling the domain, or
// one small box) gives exactly the grains of the whole-domain generation in those boxes,
// with the same uids and bit-identical values; and across MPI ranks, each asking for its
// slab, the union gathered on rank 0 is exactly the serial list.
#include "core/mpi/Comm.hpp"
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

core::AABB const kDomain = box(Vec3::Zero(), Vec3(16, 16, 12));
Periodic const kPeriodic{true, true, false};

/// Every kind, with skips across entries and across the periodic faces: boulders crossing
/// the x and y faces, an sc lattice with random velocities under an agglomerate that packs
/// around it, an hcp lattice around all of them, and a file whose grains partly overlap
/// (uid 0 sits above the hcp's top layer across the x and y faces and is kept).
struct Scene {
    TempFile file{"split_scene.csv", "uid,x,y,z,vx,vy,vz,radius,mass\n"
                                     "3,8.1,8.2,10.6,0.1,0,0,0.4,0.2\n"
                                     "0,15.9,0.2,11.7,0,0,-1,0.25,0.1\n"
                                     "7,2.0,14.0,9.0,0,0.5,0,0.3,0.05\n"
                                     "1,4.05,4.05,2.05,0,0,0,0.5,0.3\n"};
    std::vector<ParticleSpec> specs;
    Scene() {
        specs.push_back(sphereList({Vec3(1.2, 8.3, 6.1), Vec3(14.9, 15.1, 3.4)}, {2.7, 1.9}));
        specs.push_back(lattice(LatticeKind::SimpleCubic, 1.0, 0.45,
                                box(Vec3::Zero(), Vec3(16, 16, 6)),
                                particles::RandomVelocity{-0.2, 0.2, 11}));
        specs.push_back(agglomerate(Vec3(8.1, 8.2, 7.5), 2.8, 0.2, 0.35, 120, 7));
        specs.push_back(lattice(LatticeKind::HexagonalClosePacked, 0.9, 0.45,
                                box(Vec3(0, 0, 6), Vec3(16, 16, 12))));
        particles::FileSpec f;
        f.path = file.path();
        specs.push_back(withType(f, 4));
    }
};

std::vector<GrainInit> inBoxes(std::vector<GrainInit> const& all,
                               std::vector<core::AABB> const& boxes) {
    std::vector<GrainInit> out;
    for (auto const& g : all)
        if (std::any_of(boxes.begin(), boxes.end(),
                        [&](core::AABB const& b) { return b.contains(g.position); }))
            out.push_back(g);
    return out;
}

/// The domain cut at the given planes into nx * ny * nz boxes.
std::vector<core::AABB> tiles(std::vector<double> const& xs, std::vector<double> const& ys,
                              std::vector<double> const& zs) {
    std::vector<core::AABB> out;
    for (std::size_t k = 0; k + 1 < zs.size(); ++k)
        for (std::size_t j = 0; j + 1 < ys.size(); ++j)
            for (std::size_t i = 0; i + 1 < xs.size(); ++i)
                out.push_back(
                    box(Vec3(xs[i], ys[j], zs[k]), Vec3(xs[i + 1], ys[j + 1], zs[k + 1])));
    return out;
}

} // namespace

TEST(Split, BoxSetsGiveTheSubsetOfTheGlobalList) {
    Scene const scene;
    auto const global = particles::generateGrains(scene.specs, kDomain, kPeriodic);
    // Every entry contributes, and skipping happened in every later entry.
    for (std::uint32_t e = 0; e < 5; ++e)
        EXPECT_TRUE(std::any_of(global.grains.begin(), global.grains.end(),
                                [&](GrainInit const& g) { return g.entry == e; }))
            << "entry " << e;
    EXPECT_EQ(std::count_if(global.grains.begin(), global.grains.end(),
                            [](GrainInit const& g) { return g.entry == 2; }),
              120);
    EXPECT_TRUE(std::is_sorted(global.grains.begin(), global.grains.end(),
                               [](auto const& a, auto const& b) { return a.uid < b.uid; }));

    std::vector<std::vector<core::AABB>> const sets{
        {kDomain},
        tiles({0, 8, 16}, {0, 16}, {0, 12}),
        tiles({0, 7.3, 16}, {0, 9.1, 16}, {0, 5.5, 12}),
        tiles({0, 3, 11.7, 16}, {0, 2.25, 16}, {0, 6, 12}),
        {box(Vec3(0, 0, 0), Vec3(2, 3, 4))},      // one corner block
        {box(Vec3(7, 7, 6), Vec3(9.5, 9.5, 9))},  // inside the agglomerate
        {box(Vec3(13, 13, 2), Vec3(16, 16, 5))}}; // at the boulder's periodic corner
    for (std::size_t s = 0; s < sets.size(); ++s) {
        auto const part = particles::generateGrains(scene.specs, kDomain, kPeriodic, sets[s]);
        EXPECT_EQ(part.entryUidBegin, global.entryUidBegin);
        expectSameGrains(part.grains, inBoxes(global.grains, sets[s]),
                         "box set " + std::to_string(s));
        // Box by box, each box alone, and the union again.
        std::vector<GrainInit> joined;
        for (auto const& b : sets[s]) {
            std::vector<core::AABB> const one{b};
            auto const piece = particles::generateGrains(scene.specs, kDomain, kPeriodic, one);
            joined.insert(joined.end(), piece.grains.begin(), piece.grains.end());
        }
        std::sort(joined.begin(), joined.end(),
                  [](auto const& a, auto const& b) { return a.uid < b.uid; });
        expectSameGrains(joined, part.grains, "box set " + std::to_string(s) + " one by one");
    }
}

TEST(Split, SlabsOverRanksUnionToTheSerialList) {
    core::Comm world;
    Scene const scene;
    int const p = world.size();
    int const r = world.rank();
    // Slab r of the x axis; the last slab ends exactly at the domain face.
    double const x0 = 16.0 * r / p;
    double const x1 = r + 1 == p ? 16.0 : 16.0 * (r + 1) / p;
    std::vector<core::AABB> const slab{box(Vec3(x0, 0, 0), Vec3(x1, 16, 12))};
    auto const mine = particles::generateGrains(scene.specs, kDomain, kPeriodic, slab);
    auto const serial = particles::generateGrains(scene.specs, kDomain, kPeriodic);
    expectSameGrains(mine.grains, inBoxes(serial.grains, slab), "own slab");

    auto const all = world.gatherStrings(packGrains(mine.grains), 0);
    if (r == 0) {
        std::vector<GrainInit> joined;
        for (auto const& s : all) {
            auto const part = unpackGrains(s);
            joined.insert(joined.end(), part.begin(), part.end());
        }
        std::sort(joined.begin(), joined.end(),
                  [](auto const& a, auto const& b) { return a.uid < b.uid; });
        expectSameGrains(joined, serial.grains,
                         "union of the slabs of " + std::to_string(p) + " ranks");
    }
}
