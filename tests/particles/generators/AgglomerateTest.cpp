// Agglomerates: count, radii, containment, no overlap (brute force), determinism for a seed,
// packing around earlier entries, periodic wrap, and the error for an impossible packing.
#include "core/random/CounterRng.hpp"
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

core::AABB const kDomain = box(Vec3::Zero(), Vec3(20, 20, 20));

std::vector<GrainInit> pack(std::vector<ParticleSpec> const& specs,
                            Periodic const& periodic = {false, false, false}) {
    return particles::generateGrains(specs, kDomain, periodic).grains;
}

void expectValidAgglomerate(std::vector<GrainInit> const& g, AgglomerateSpec const& a,
                            Periodic const& periodic) {
    for (std::size_t i = 0; i < g.size(); ++i) {
        EXPECT_GE(g[i].radius, a.grainRadiusMin);
        if (a.grainRadiusMin < a.grainRadiusMax)
            EXPECT_LT(g[i].radius, a.grainRadiusMax);
        else
            EXPECT_EQ(g[i].radius, a.grainRadiusMax);
        double const fromCentre = minImage(g[i].position, a.center, kDomain, periodic).norm();
        EXPECT_LE(fromCentre + g[i].radius, a.radius * (1.0 + 1e-12)) << "grain " << i;
        EXPECT_EQ(g[i].velocity, a.velocity);
        for (std::size_t j = i + 1; j < g.size(); ++j)
            EXPECT_FALSE(overlapMinImage(g[i], g[j], kDomain, periodic)) << i << " " << j;
    }
}

} // namespace

TEST(Agglomerate, PackedWithoutOverlapInsideTheSphere) {
    auto const spec = agglomerate(Vec3(10, 10, 10), 5.0, 0.3, 0.6, 300, 3);
    auto const& a = std::get<AgglomerateSpec>(spec.kind);
    auto const g = pack({spec});
    ASSERT_EQ(g.size(), 300u);
    for (std::size_t i = 0; i < g.size(); ++i) {
        EXPECT_EQ(g[i].uid, i);
        // The radius is the first draw of the grain's stream.
        core::random::CounterRng rng(3, i);
        EXPECT_EQ(g[i].radius, rng.uniform(0.3, 0.6));
        EXPECT_EQ(g[i].type, 2u);
    }
    expectValidAgglomerate(g, a, {false, false, false});
    // Requested packing fraction about 300 * E[r^3] / R^3 = 0.243: the grains fill the
    // sphere, not a shell or a corner.
    Vec3 centroid = Vec3::Zero();
    for (auto const& x : g)
        centroid += x.position / 300.0;
    EXPECT_LT((centroid - a.center).norm(), 0.5);
}

TEST(Agglomerate, DeterministicForASeedAndDifferentForAnother) {
    auto const one = pack({agglomerate(Vec3(10, 10, 10), 4.0, 0.3, 0.5, 150, 9)});
    auto const again = pack({agglomerate(Vec3(10, 10, 10), 4.0, 0.3, 0.5, 150, 9)});
    expectSameGrains(again, one, "same seed");
    auto const other = pack({agglomerate(Vec3(10, 10, 10), 4.0, 0.3, 0.5, 150, 10)});
    ASSERT_EQ(other.size(), one.size());
    std::size_t samePositions = 0;
    for (std::size_t i = 0; i < one.size(); ++i)
        samePositions += one[i].position == other[i].position ? 1 : 0;
    EXPECT_EQ(samePositions, 0u);
}

TEST(Agglomerate, EqualRadiiAndZeroCount) {
    auto const g = pack({agglomerate(Vec3(10, 10, 10), 3.0, 0.4, 0.4, 80, 1),
                         agglomerate(Vec3(3, 3, 3), 1.0, 0.1, 0.2, 0, 1)});
    ASSERT_EQ(g.size(), 80u);
    for (auto const& x : g)
        EXPECT_EQ(x.radius, 0.4);
    expectValidAgglomerate(
        g, std::get<AgglomerateSpec>(agglomerate(Vec3(10, 10, 10), 3.0, 0.4, 0.4, 80, 1).kind),
        {false, false, false});
}

TEST(Agglomerate, PacksAroundEarlierEntriesAndAcrossPeriodicFaces) {
    // A boulder inside the sphere and a lattice under it are obstacles; the sphere crosses
    // the periodic x and y faces, so its grains wrap and overlaps use the minimum image.
    Periodic const periodic{true, true, false};
    auto const spec = agglomerate(Vec3(0.5, 19.0, 10.0), 4.0, 0.25, 0.45, 200, 5);
    std::vector<ParticleSpec> const specs{
        sphereList({Vec3(0.2, 19.5, 10.0)}, {1.5}),
        lattice(LatticeKind::SimpleCubic, 1.0, 0.45, box(Vec3::Zero(), Vec3(20, 20, 8))), spec};
    auto const all = pack(specs, periodic);
    std::vector<GrainInit> earlier;
    std::vector<GrainInit> grains;
    for (auto const& g : all)
        (g.entry == 2 ? grains : earlier).push_back(g);
    ASSERT_EQ(grains.size(), 200u);
    expectValidAgglomerate(grains, std::get<AgglomerateSpec>(spec.kind), periodic);
    bool wrapped = false;
    for (auto const& g : grains) {
        EXPECT_TRUE(kDomain.contains(g.position));
        wrapped = wrapped || g.position.x() > 10.0 || g.position.y() < 10.0;
        for (auto const& e : earlier)
            EXPECT_FALSE(overlapMinImage(g, e, kDomain, periodic)) << g.uid << " " << e.uid;
    }
    EXPECT_TRUE(wrapped);
}

TEST(Agglomerate, ImpossiblePackingIsAnInputErrorStatingTheFraction) {
    // 60 grains of radius 0.5 in a sphere of radius 2: fraction 60 / 64 = 0.94, far above the
    // random-sequential-insertion limit.
    auto spec = agglomerate(Vec3(10, 10, 10), 2.0, 0.5, 0.5, 60, 1);
    std::get<AgglomerateSpec>(spec.kind).maxAttempts = 200;
    std::string const msg = inputErrorOf([&] { (void)pack({spec}); });
    EXPECT_NE(msg.find("particles[0]"), std::string::npos) << msg;
    EXPECT_NE(msg.find("packing fraction"), std::string::npos) << msg;
    EXPECT_NE(msg.find("0.9375"), std::string::npos) << msg;
    EXPECT_NE(msg.find("200 attempts"), std::string::npos) << msg;
    // More grain volume than the sphere: refused before trying.
    auto full = agglomerate(Vec3(10, 10, 10), 2.0, 0.5, 0.5, 70, 1);
    std::string const msgFull = inputErrorOf([&] { (void)pack({full}); });
    EXPECT_NE(msgFull.find("cannot fit"), std::string::npos) << msgFull;
    EXPECT_NE(msgFull.find("1.0938"), std::string::npos) << msgFull;
}
