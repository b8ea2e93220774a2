// [[walls]] entries: every shape and motion parses to what it says; bad values and keys a
// shape does not have get one message naming the key.
#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace regolith;
using particles::WallShape;

namespace {

/// A scene in the box [0, 8]^3 (periodic along x with `periodicX`) with one wall, `entry`.
apps::SceneDescription sceneWith(std::string const& entry, bool periodicX = false) {
    std::string const text = std::string("[domain]\nmin = [0, 0, 0]\nmax = [8, 8, 8]\n") +
                             (periodicX ? "periodic = [true, false, false]\n" : "") +
                             "[time]\ndt = 0.01\nsteps = 0\n[[walls]]\n" + entry + "\n";
    return apps::parseScene(core::ConfigTable::fromString(text, "w.toml"), "w.toml");
}

/// The message of the InputError sceneWith(entry) throws.
std::string errorOf(std::string const& entry, bool periodicX = false) {
    try {
        (void)sceneWith(entry, periodicX);
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(WallSection, ShapesAndMotions) {
    auto const plane = sceneWith("point = [0, 0, 1]\nnormal = [0, 0, 2]").walls[0];
    EXPECT_EQ(plane.geometry.shape, WallShape::Plane);
    EXPECT_EQ(plane.geometry.normal, core::Vec3(0, 0, 1));
    EXPECT_FALSE(plane.motion.moves());
    auto const drum = sceneWith("shape = \"cylinder\"\npoint = [4, 0, 4]\naxis = [0, 2, 0]\n"
                                "radius = 3\nside = \"outer\"\nangular_velocity = [0, 1.5, 0]")
                          .walls[0];
    EXPECT_EQ(drum.geometry.shape, WallShape::Cylinder);
    EXPECT_EQ(drum.geometry.normal, core::Vec3(0, 1, 0));
    EXPECT_EQ(drum.geometry.radius, 3.0);
    EXPECT_FALSE(drum.geometry.inner);
    EXPECT_EQ(drum.motion.angularVelocity, core::Vec3(0, 1.5, 0));
    EXPECT_EQ(drum.motion.centre, core::Vec3(4, 0, 4)); // axis_point defaults to point
    auto const plate =
        sceneWith("shape = \"rectangle\"\npoint = [4, 4, 1]\nnormal = [0, 0, 1]\nsize = [2, 4]\n"
                  "edge = [1, 0, 1]\nvelocity = [0, 0, 0.5]\namplitude = [0, 0, 0.01]\n"
                  "frequency = 20\naxis_point = [1, 1, 1]\ntype = 2")
            .walls[0];
    EXPECT_EQ(plate.geometry.shape, WallShape::Rectangle);
    EXPECT_EQ(plate.geometry.halfSize[0], 1.0);
    EXPECT_EQ(plate.geometry.halfSize[1], 2.0);
    EXPECT_EQ(plate.geometry.edge, core::Vec3(1, 0, 0)); // its part perpendicular to the normal
    EXPECT_EQ(plate.motion.velocity, core::Vec3(0, 0, 0.5));
    EXPECT_EQ(plate.motion.amplitude, core::Vec3(0, 0, 0.01));
    EXPECT_EQ(plate.motion.frequency, 20.0);
    EXPECT_EQ(plate.motion.centre, core::Vec3(1, 1, 1));
    EXPECT_EQ(plate.type, 2u);
    auto const disc =
        sceneWith("shape = \"disc\"\npoint = [4, 4, 1]\nnormal = [0, 0, 1]\nradius = 0.5").walls[0];
    EXPECT_EQ(disc.geometry.shape, WallShape::Disc);
    EXPECT_EQ(disc.geometry.radius, 0.5);
}

TEST(WallSection, BadWallsGetOneClearMessage) {
    EXPECT_EQ(errorOf("point = [0, 0, 0]\nnormal = [0, 0, 0]"),
              "w.toml:9: walls[0].normal: expected a non-zero vector of 3 finite numbers, got "
              "[0, 0, 0]");
    EXPECT_EQ(errorOf("shape = \"sphere\"\npoint = [0, 0, 0]"),
              "w.toml:8: walls[0].shape: expected one of \"plane\", \"rectangle\", \"disc\", "
              "\"cylinder\", got \"sphere\"");
    EXPECT_EQ(errorOf("shape = \"cylinder\"\npoint = [4, 4, 4]\naxis = [0, 0, 1]\nradius = -1"),
              "w.toml:11: walls[0].radius: expected a positive finite length, got -1");
    EXPECT_EQ(errorOf("shape = \"cylinder\"\npoint = [4, 4, 4]\naxis = [0, 0, 1]\n"
                      "normal = [0, 0, 1]\nradius = 1"),
              "w.toml:11: walls[0].normal: does not apply to shape = \"cylinder\"");
    EXPECT_EQ(errorOf("point = [0, 0, 0]\nnormal = [0, 0, 1]\nradius = 1"),
              "w.toml:10: walls[0].radius: does not apply to shape = \"plane\"");
    EXPECT_EQ(errorOf("shape = \"rectangle\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
                      "size = [1, 0]"),
              "w.toml:11: walls[0].size: expected two positive finite side lengths [a, b], got "
              "[1, 0]");
    EXPECT_EQ(errorOf("shape = \"rectangle\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
                      "size = [1, 1]\nedge = [0, 0, -2]"),
              "w.toml:12: walls[0].edge: expected a vector of 3 finite numbers not parallel to "
              "the normal, got [0, 0, -2]");
    EXPECT_EQ(errorOf("point = [0, 0, 0]\nnormal = [0, 0, 1]\namplitude = [0, 0, 1]"),
              "w.toml:10: walls[0].amplitude: a shake needs both amplitude and frequency");
    // A wall must repeat itself along a periodic axis.
    EXPECT_EQ(errorOf("shape = \"disc\"\npoint = [4, 4, 4]\nnormal = [0, 0, 1]\nradius = 1", true),
              "w.toml:9: walls[0].shape: a disc ends inside the domain, which is periodic along "
              "x (domain.periodic): grains would pass round it through the periodic face; use a "
              "plane, or an open domain");
    EXPECT_EQ(errorOf("point = [0, 0, 0]\nnormal = [0, 0, 1]\nangular_velocity = [0, 1, 0]", true),
              "w.toml:11: walls[0].angular_velocity: a wall in a domain periodic along x may turn "
              "about x only (domain.periodic)");
    EXPECT_EQ(
        errorOf("shape = \"cylinder\"\npoint = [4, 4, 4]\naxis = [0, 0, 1]\nradius = 1", true),
        "w.toml:11: walls[0].axis: a cylinder in a domain periodic along x must lie along x "
        "(domain.periodic)");
}
