// The batched sphere-wall evaluation (SpringDashpotWallBatch) against evaluateWallsWith one
// contact at a time: the same sink calls with the same bits, the same loads on the walls, and
// the same springs and stamps in the histories, over several passes of spheres resting on a
// floor, against a tilted plane, a moving plane and the inside of a turning drum; two
// materials (the walls' own) and one, model A's rolling couple and model C's spring, more
// contacts than one batch holds, and spheres touching two walls at once (a second touch
// inserting an entry into the history the first one's entry lives in).
#include "particles/kernels/SpringDashpotWallBatch.hpp"

#include "particles/detection/ContactDetector.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "tests/particles/ParticleTestUtil.hpp"
#include "tests/particles/SharesTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

/// Grains of type 0 and walls of type 1 (with two materials), model C optionally, rolling
/// resistance between grains and walls.
SpringDashpot grainsAndWalls(bool twoMaterials, bool modelC) {
    LinearContactParams grain;
    grain.stiffness = 2000.0;
    grain.tangentialStiffness = 600.0;
    grain.restitution = 0.7;
    grain.friction = 0.5;
    grain.rollingFriction = 0.05;
    grain.rollingSpring.enabled = modelC;
    if (!twoMaterials)
        return SpringDashpot{MaterialTable<LinearContactParams>(1, grain)};
    MaterialTable<LinearContactParams> table(2);
    table.set(0, 0, grain);
    LinearContactParams wall = grain;
    wall.stiffness = 5000.0;
    wall.friction = 0.3;
    wall.rollingFriction = 0.2;
    wall.rollingSpring.stiffness = 400.0;
    wall.tangentialDampingRatio = 0.3;
    table.set(0, 1, wall);
    table.set(1, 1, wall);
    return SpringDashpot{table};
}

/// A floor, a plane tilted over it, a plane moving up and sliding, and a drum turning about
/// the z axis; walls of type `type`.
WallList scene(std::uint32_t type) {
    WallList walls;
    walls.add(Vec3(0.0, 0.0, 0.0), Vec3::UnitZ(), type);
    walls.add(Vec3(0.0, 0.0, 0.3), Vec3(1.0, 0.0, 1.0).normalized(), type);
    Wall moving;
    moving.geometry.point = Vec3(0.0, 5.6, 0.0);
    moving.geometry.normal = -Vec3::UnitY();
    moving.motion.velocity = Vec3(0.4, -0.1, 0.0);
    moving.motion.angularVelocity = Vec3(0.0, 0.0, 0.2);
    moving.type = type;
    walls.add(moving);
    Wall drum;
    drum.geometry.shape = WallShape::Cylinder;
    drum.geometry.point = Vec3(3.0, 3.0, 0.0);
    drum.geometry.normal = Vec3::UnitZ();
    drum.geometry.radius = 2.6;
    drum.motion.angularVelocity = Vec3(0.0, 0.0, 1.5);
    drum.motion.centre = drum.geometry.point;
    drum.type = type;
    walls.add(drum);
    walls.moveTo(0.1);
    return walls;
}

/// Spheres on the floor in and around the drum, overlapping the walls by up to a tenth of a
/// radius, moving and spinning.
ParticleStorage spheres(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    ParticleStorage ps;
    for (std::size_t k = 0; k < 260; ++k) {
        double const r = 0.2 + 0.1 * u(rng);
        Vec3 const x(6.0 * u(rng), 6.0 * u(rng), r * (0.9 + 0.1 * u(rng)));
        ParticleInit p = sphere(makeUid(0, k + 1), x, r, 1.0 + u(rng),
                                Vec3(u(rng) - 0.5, u(rng) - 0.5, 0.2 * (u(rng) - 0.5)));
        p.angularVelocity = 6.0 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        ps.add(p);
    }
    return ps;
}

void expectSameAsEvaluateWallsWith(SpringDashpot const& model, std::uint32_t wallType) {
    SCOPED_TRACE(model.hasRollingSpring() ? "model C" : "model A");
    double const dt = 2e-3;
    ParticleStorage one = spheres(3);
    WallList oneWalls = scene(wallType);
    ContactDetector detector;
    ContactList contacts;
    detector.detect(one, oneWalls, everywhere(), contacts);
    ASSERT_GT(contacts.walls.size(), SpringDashpotWallBatch::kCapacity);
    std::vector<std::size_t> touches(one.size(), 0);
    for (WallContact const& c : contacts.walls)
        ++touches[c.particle];
    ASSERT_GT(std::count_if(touches.begin(), touches.end(), [](std::size_t t) { return t > 1; }),
              0); // a sphere touching two walls
    ParticleStorage batched = one;
    WallList batchedWalls = oneWalls;
    SpringDashpotWallBatch batch;
    for (std::uint32_t stamp = 1; stamp <= 4; ++stamp) {
        detector.detect(one, oneWalls, everywhere(), contacts);
        std::vector<Share> expected, got;
        oneWalls.resetForces();
        batchedWalls.resetForces();
        evaluateWallsWith(one, oneWalls, contacts.walls, model, dt, stamp, recordInto(expected));
        batch.evaluate(batched, batchedWalls, contacts.walls, model, dt, stamp, recordInto(got));
        expectSameShares(got, expected);
        for (std::size_t w = 0; w < oneWalls.size(); ++w) {
            EXPECT_TRUE(sameBits(batchedWalls.load(w).force, oneWalls.load(w).force)) << w;
            EXPECT_TRUE(sameBits(batchedWalls.load(w).torque, oneWalls.load(w).torque)) << w;
            EXPECT_EQ(std::bit_cast<std::uint64_t>(batchedWalls.load(w).power),
                      std::bit_cast<std::uint64_t>(oneWalls.load(w).power))
                << w;
        }
        EXPECT_NE(oneWalls.load(2).power, 0.0); // the moving wall's terms were exercised
        expectSameHistories(batched, one);
        for (ParticleStorage* ps : {&one, &batched})
            for (std::size_t k = 0; k < ps->size(); ++k) {
                ps->position(k) += dt * ps->velocity(k);
                ps->history(k).keepOnly(stamp);
            }
    }
}

} // namespace

TEST(SpringDashpotWallBatch, SameSharesLoadsAndSpringsAsEvaluateWallsWith) {
    expectSameAsEvaluateWallsWith(grainsAndWalls(true, false), 1);
}

TEST(SpringDashpotWallBatch, SameWithOneMaterial) {
    expectSameAsEvaluateWallsWith(grainsAndWalls(false, false), 0);
}

TEST(SpringDashpotWallBatch, SameWithModelC) {
    expectSameAsEvaluateWallsWith(grainsAndWalls(true, true), 1);
    expectSameAsEvaluateWallsWith(grainsAndWalls(false, true), 0);
}
