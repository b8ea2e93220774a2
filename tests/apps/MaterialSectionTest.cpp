// [[materials]] and the material keys of [contact] (apps/regolith/MaterialSection.hpp): parsed
// per type, each bad input refused with one message naming the key, and the contact model's
// table filled from them with the mixing rules.
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/SpringDashpot.hpp"

#include <gtest/gtest.h>

#include <string>
#include <variant>

using namespace regolith;

namespace {

// Two grains of types 0 and 1 on a floor of type 2.
constexpr char const* kHead = R"([domain]
min = [0, 0, 0]
max = [4, 4, 4]
[time]
dt = 1e-4
steps = 1
[[particles]]
kind = "list"
position = [[1, 1, 1]]
radius = 0.5
density = 1.0
[[particles]]
kind = "list"
position = [[3, 3, 1]]
radius = 0.5
density = 1.0
type = 1
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
type = 2
)";

constexpr char const* kThreeMaterials = R"(
[[materials]]
stiffness = 100.0
restitution = 0.9
friction = 0.2
[[materials]]
stiffness = 400.0
restitution = 0.4
friction = 0.8
[[materials]]
type = 2
stiffness = 900.0
restitution = 0.5
friction = 0.5
rolling_friction = 0.1
)";

apps::SceneDescription parse(std::string const& tail) {
    auto const root = core::ConfigTable::fromString(std::string(kHead) + tail, "m.toml");
    return apps::parseScene(root, "m.toml");
}

std::string errorOf(std::string const& tail) {
    try {
        (void)parse(tail);
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(Materials, EveryTypeHasItsOwnAndUnlikePairsMix) {
    auto const scene = parse(kThreeMaterials);
    ASSERT_TRUE(scene.materials.perType);
    ASSERT_EQ(scene.materials.types.size(), 3U);
    EXPECT_EQ(scene.materials.of(1).friction, 0.8);
    EXPECT_EQ(scene.materials.of(2).rollingFriction, 0.1);
    auto const model = apps::makeContactModel(scene);
    auto const* held = model.get<particles::SpringDashpot>();
    ASSERT_NE(held, nullptr);
    auto const& table = held->materials();
    ASSERT_EQ(table.numTypes(), 3U);
    EXPECT_EQ(table(0, 0).restitution, 0.9);
    EXPECT_DOUBLE_EQ(table(0, 1).stiffness, 200.0);
    EXPECT_DOUBLE_EQ(table(0, 1).restitution, 0.6);
    EXPECT_DOUBLE_EQ(table(1, 0).friction, 0.4);
    EXPECT_DOUBLE_EQ(table(1, 2).stiffness, 600.0);
}

TEST(Materials, ContactAloneIsEveryTypesMaterial) {
    auto const scene = parse("[contact]\nstiffness = 50.0\nfriction = 0.3\n");
    EXPECT_FALSE(scene.materials.perType);
    auto const model = apps::makeContactModel(scene);
    auto const* held = model.get<particles::SpringDashpot>();
    ASSERT_NE(held, nullptr);
    auto const& table = held->materials();
    ASSERT_EQ(table.numTypes(), 3U); // types 0 to 2 are used
    for (std::uint32_t a = 0; a < 3; ++a)
        for (std::uint32_t b = 0; b < 3; ++b) {
            EXPECT_EQ(table(a, b).stiffness, 50.0);
            EXPECT_EQ(table(a, b).tangentialStiffness, 2.0 / 7.0 * 50.0);
            EXPECT_EQ(table(a, b).restitution, 0.9);
            EXPECT_EQ(table(a, b).friction, 0.3);
        }
}

TEST(Materials, HertzTakesYoungsModulusAndPoissonRatio) {
    auto const scene = parse("[contact]\nmodel = \"hertz\"\n"
                             "[[materials]]\nyoungs_modulus = 1e7\npoisson_ratio = 0.25\n"
                             "[[materials]]\nyoungs_modulus = 4e7\npoisson_ratio = 0.5\n"
                             "[[materials]]\nyoungs_modulus = 2e8\npoisson_ratio = 0.3\n");
    auto const model = apps::makeContactModel(scene);
    auto const* held = model.get<particles::HertzMindlin>();
    ASSERT_NE(held, nullptr);
    auto const& table = held->materials();
    EXPECT_DOUBLE_EQ(table(0, 0).effectiveYoungsModulus, 1e7 / (2.0 * (1.0 - 0.0625)));
    EXPECT_DOUBLE_EQ(table(0, 1).effectiveYoungsModulus, 1.0 / ((1.0 - 0.0625) / 1e7 + 0.75 / 4e7));
}

TEST(Materials, BadInputIsRefusedNamingTheKey) {
    EXPECT_EQ(errorOf(std::string(kThreeMaterials) + "[contact]\nfriction = 0.5\n"),
              "m.toml:38: contact.friction: is set per material type in [[materials]] when the "
              "scene has them; move it there");
    EXPECT_EQ(errorOf("[[materials]]\nstiffness = 1.0\n[[materials]]\nstiffness = 2.0\n"),
              "m.toml:21: walls[0].type: no [[materials]] entry has type 2 (the scene defines "
              "types 0 to 1)");
    EXPECT_EQ(errorOf("[[materials]]\ntype = 1\n[[materials]]\n[[materials]]\n"),
              "m.toml:24: materials[1].type: type 1 is already materials[0]'s");
    EXPECT_EQ(errorOf("[[materials]]\ntype = 3\n"),
              "m.toml:23: materials[0].type: expected a material type from 0 to 0 (one "
              "[[materials]] entry each), got 3");
    EXPECT_EQ(errorOf("[[materials]]\nrestitution = 0\n[[materials]]\n[[materials]]\n"),
              "m.toml:23: materials[0].restitution: expected a number in (0, 1], got 0");
    EXPECT_EQ(errorOf("[contact]\nyoungs_modulus = 1e7\n"),
              "m.toml:23: contact.youngs_modulus: applies to contact.model = \"hertz\"; the "
              "spring-dashpot model's elasticity is stiffness (force / length)");
    EXPECT_EQ(errorOf("[contact]\nmodel = \"hertz\"\nstiffness = 1e7\n"),
              "m.toml:24: contact.stiffness: with contact.model = \"hertz\" a material's "
              "elasticity is youngs_modulus (E, a pressure) and poisson_ratio (nu), both "
              "required (two like grains have the effective modulus E / (2 (1 - nu^2))); "
              "stiffness = 1e+07 as the effective modulus with nu = 0.3 is youngs_modulus = "
              "1.82e+07, poisson_ratio = 0.3");
    EXPECT_EQ(errorOf("[contact]\nmodel = \"hertz\"\nyoungs_modulus = 1e7\n"),
              "m.toml:22: contact.poisson_ratio: is required with contact.model = \"hertz\" "
              "(the material's Poisson ratio, in (-1, 0.5])");
}
