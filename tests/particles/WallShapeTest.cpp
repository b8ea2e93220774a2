// Wall shapes and motions: the distance and normal of each shape, the surface velocity and
// pose of a moving wall, the reaction a wall takes and the work it does.
#include "particles/detection/ContactDetector.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/storage/WallList.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace regolith::particles;
using regolith::core::InputError;
using regolith::core::Vec3;

namespace {

constexpr double kTol = 1e-12;

void expectNear(Vec3 const& a, Vec3 const& b, double tol = kTol) {
    EXPECT_LT((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose();
}

Wall shaped(WallShape shape, Vec3 point, Vec3 normal) {
    Wall w;
    w.geometry.shape = shape;
    w.geometry.point = point;
    w.geometry.normal = normal;
    w.motion.centre = point;
    return w;
}

} // namespace

TEST(WallShape, PlaneIsAHalfSpace) {
    WallGeometry const g = shaped(WallShape::Plane, Vec3(0, 0, 1), Vec3::UnitZ()).geometry;
    EXPECT_DOUBLE_EQ(g.touch(Vec3(3, -2, 4)).distance, 3.0);
    EXPECT_DOUBLE_EQ(g.touch(Vec3(0, 0, 0.5)).distance, -0.5); // behind it
    expectNear(g.touch(Vec3(3, -2, 4)).normal, Vec3::UnitZ());
}

TEST(WallShape, RectangleIsAPlateWithEdges) {
    Wall w = shaped(WallShape::Rectangle, Vec3(1, 1, 0), Vec3::UnitZ());
    w.geometry.edge = Vec3(1, 0, 0.5); // normalised perpendicular to the normal by add
    w.geometry.halfSize[0] = 2.0;      // along x
    w.geometry.halfSize[1] = 1.0;      // along y
    WallList walls;
    WallGeometry const& g = walls[walls.add(w)].geometry;
    expectNear(g.edge, Vec3::UnitX());
    // Above the face, on either side: the distance from the plate, along +-z.
    EXPECT_NEAR(g.touch(Vec3(2, 1.5, 0.3)).distance, 0.3, kTol);
    expectNear(g.touch(Vec3(2, 1.5, -0.3)).normal, -Vec3::UnitZ());
    // Beyond the x edge (x = 3): from the nearest edge point.
    WallTouch const edge = g.touch(Vec3(3.3, 1.5, 0.4));
    EXPECT_NEAR(edge.distance, 0.5, kTol);
    expectNear(edge.normal, Vec3(0.6, 0, 0.8));
    // Beyond a corner (3, 2, 0).
    EXPECT_NEAR(g.touch(Vec3(4, 3, 1)).distance, std::sqrt(3.0), kTol);
    // In the plate's plane, inside it: touching, normal the plate's.
    EXPECT_EQ(g.touch(Vec3(1, 1, 0)).distance, 0.0);
}

TEST(WallShape, DiscIsARoundPlate) {
    Wall w = shaped(WallShape::Disc, Vec3(0, 0, 2), Vec3(0, 0, -3));
    w.geometry.radius = 1.0;
    WallList walls;
    WallGeometry const& g = walls[walls.add(w)].geometry;
    EXPECT_NEAR(g.touch(Vec3(0.5, 0.5, 1.5)).distance, 0.5, kTol);
    expectNear(g.touch(Vec3(0.5, 0.5, 1.5)).normal, -Vec3::UnitZ());
    WallTouch const rim = g.touch(Vec3(0, 4, 6)); // rim point (0, 1, 2): offset (0, 3, 4)
    EXPECT_NEAR(rim.distance, 5.0, kTol);
    expectNear(rim.normal, Vec3(0, 0.6, 0.8));
}

TEST(WallShape, CylinderInsideOrOutside) {
    Wall w = shaped(WallShape::Cylinder, Vec3(1, 0, 0), Vec3(0, 0, 2));
    w.geometry.radius = 2.0;
    WallList walls;
    walls.add(w);
    w.geometry.inner = false;
    walls.add(w);
    Vec3 const x(1.5, 0, 7); // half a unit off the axis, anywhere along it
    WallTouch const in = walls[0].geometry.touch(x);
    EXPECT_NEAR(in.distance, 1.5, kTol);
    expectNear(in.normal, -Vec3::UnitX()); // from the shell towards the axis
    WallTouch const out = walls[1].geometry.touch(Vec3(1, -3, -1));
    EXPECT_NEAR(out.distance, 1.0, kTol);
    expectNear(out.normal, -Vec3::UnitY());
    EXPECT_NEAR(walls[1].geometry.touch(x).distance, -1.5, kTol); // inside the solid
}

TEST(WallShape, BadShapesAreRefused) {
    WallList walls;
    Wall w = shaped(WallShape::Cylinder, Vec3::Zero(), Vec3::UnitZ());
    w.geometry.radius = -1.0;
    EXPECT_THROW(walls.add(w), InputError);
    w = shaped(WallShape::Rectangle, Vec3::Zero(), Vec3::UnitZ());
    w.geometry.halfSize[0] = w.geometry.halfSize[1] = 1.0;
    w.geometry.edge = Vec3(0, 0, 3); // along the normal
    EXPECT_THROW(walls.add(w), InputError);
    EXPECT_THROW(walls.add(Vec3::Zero(), Vec3::Zero()), InputError);
    EXPECT_TRUE(walls.empty());
}

TEST(WallMotion, RotatingDrumSurfaceVelocityAndPose) {
    // A drum about the z axis through (1, 0, 0), turning at 2 rad/time: the shell stays put,
    // its material moves at omega x r.
    Wall w = shaped(WallShape::Cylinder, Vec3(1, 0, 0), Vec3::UnitZ());
    w.geometry.radius = 1.0;
    w.motion.angularVelocity = Vec3(0, 0, 2);
    WallList walls;
    walls.add(w);
    EXPECT_TRUE(walls.moving());
    walls.moveTo(0.7);
    Wall const& d = walls[0];
    expectNear(d.geometry.point, Vec3(1, 0, 0));
    expectNear(d.surfaceVelocity(Vec3(2, 0, 0.3)), Vec3(0, 2, 0));
    // A plane turning about an axis point off it: its normal turns, its point moves round.
    Wall p = shaped(WallShape::Plane, Vec3(1, 0, 0), Vec3::UnitX());
    p.motion.centre = Vec3::Zero();
    p.motion.angularVelocity = Vec3(0, 0, std::numbers::pi); // half a turn per time
    walls.add(p);
    walls.moveTo(0.5); // a quarter turn
    expectNear(walls[1].geometry.normal, Vec3::UnitY());
    expectNear(walls[1].geometry.point, Vec3::UnitY());
}

TEST(WallMotion, TranslationAndShake) {
    Wall w = shaped(WallShape::Plane, Vec3::Zero(), Vec3::UnitZ());
    w.motion.velocity = Vec3(0.5, 0, 0);
    w.motion.amplitude = Vec3(0, 0, 0.01);
    w.motion.frequency = 5.0;
    WallList walls;
    walls.add(w);
    double const t = 0.03;
    walls.moveTo(t);
    double const phase = 2 * std::numbers::pi * 5.0 * t;
    expectNear(walls[0].geometry.point, Vec3(0.5 * t, 0, 0.01 * std::sin(phase)));
    expectNear(walls[0].surfaceVelocity(Vec3(3, 4, 0)),
               Vec3(0.5, 0, 0.01 * 2 * std::numbers::pi * 5.0 * std::cos(phase)));
    // Unmoved walls stay as added.
    WallList fixed;
    fixed.add(Vec3(0, 0, 1), Vec3::UnitZ());
    EXPECT_FALSE(fixed.moving());
    fixed.moveTo(10.0);
    expectNear(fixed[0].geometry.point, Vec3(0, 0, 1));
    expectNear(fixed[0].surfaceVelocity(Vec3(5, 5, 1)), Vec3::Zero());
}

TEST(WallList, ReactionTorqueAndWork) {
    // A floor moving up at 2 pushed down by 3 at (1, 0, 0), turning about the origin.
    Wall w = shaped(WallShape::Plane, Vec3::Zero(), Vec3::UnitZ());
    w.motion.velocity = Vec3(0, 0, 2);
    WallList walls;
    walls.add(w);
    walls.moveTo(0.0);
    walls.addReaction(0, Vec3(1, 0, 0), Vec3(0, 0, 3), Vec3::Zero());
    expectNear(walls.load(0).force, Vec3(0, 0, -3));
    expectNear(walls.load(0).torque, Vec3(0, 3, 0)); // (1,0,0) x (0,0,-3)
    EXPECT_DOUBLE_EQ(walls.load(0).power, 6.0);
    walls.restartWork();
    walls.resetForces();
    walls.addReaction(0, Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3::Zero()); // power 2
    walls.addWork(0.5);
    EXPECT_DOUBLE_EQ(walls.work(0), 0.5 * 0.5 * (6.0 + 2.0));
}

TEST(WallContact, SeesTheSurfaceVelocityOfARotatingDrum) {
    // A grain at rest inside a drum of radius 2 about z, touching the shell at (2, 0, 0): the
    // shell's material passes it at omega x r = (0, 3, 0) (1.5 rad/time).
    Wall w = shaped(WallShape::Cylinder, Vec3::Zero(), Vec3::UnitZ());
    w.geometry.radius = 2.0;
    w.motion.angularVelocity = Vec3(0, 0, 1.5);
    WallList walls;
    walls.add(w);
    walls.moveTo(0.25);
    ParticleStorage ps;
    ps.add(test::sphere(1, Vec3(1.55, 0, 0), 0.5, 1.0));
    ContactDetector detector(DetectorConfig{});
    ContactList contacts;
    detector.detect(ps, walls, regolith::core::AABB{Vec3(-3, -3, -3), Vec3(3, 3, 3)}, contacts);
    ASSERT_EQ(contacts.walls.size(), 1u);
    WallContact const& c = contacts.walls[0];
    EXPECT_NEAR(c.penetration, 0.05, kTol);
    expectNear(c.normal, -Vec3::UnitX());
    ContactState const s = wallState(ps, walls, c);
    // The grain's velocity relative to the wall at the contact point, the middle of the
    // overlap (2.025, 0, 0).
    expectNear(s.relativeVelocity, Vec3(0, -1.5 * 2.025, 0));
    expectNear(s.relativeAngularVelocity, Vec3(0, 0, -1.5));
}
