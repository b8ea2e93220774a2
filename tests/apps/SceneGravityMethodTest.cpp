// A self-gravity method registered by a program is a gravity.self of the scene like the
// built-in ones: its own [gravity] keys are read (and checked) when it is the scene's method,
// and the scene's error for an unknown method lists it.
#include "apps/regolith/SceneSections.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "tests/apps/SceneFixture.hpp"

#include <gtest/gtest.h>

#include <any>
#include <cstdint>
#include <string>

using namespace regolith;
using namespace regolith::apps::test;

namespace {

/// A method known to the scene only (never run here): one key of its own, `sweeps` >= 1.
coupling::GravityMethodEntry sweepsMethod() {
    coupling::GravityMethodEntry e;
    e.name = "sweeps";
    e.softens = true;
    e.readKeys = [](core::ConfigTable const& gravity) -> std::any {
        return gravity.getOrIf<std::int64_t>(
            "sweeps", 2, [](std::int64_t n) { return n >= 1; }, "a number of sweeps >= 1");
    };
    e.make = [](coupling::GravityMethodInput const&) -> std::unique_ptr<coupling::GravityMethod> {
        return nullptr;
    };
    return e;
}

bool const kRegistered = (coupling::registerGravityMethod(sweepsMethod()), true);

} // namespace

TEST(SceneGravityMethod, OwnKeysRead) {
    ASSERT_TRUE(kRegistered);
    auto const s = parse({"gravity.self=sweeps", "gravity.sweeps=5"});
    EXPECT_EQ(s.gravity.self, "sweeps");
    EXPECT_EQ(std::any_cast<std::int64_t>(s.gravity.methodOptions), 5);
    EXPECT_EQ(std::any_cast<std::int64_t>(parse({"gravity.self=sweeps"}).gravity.methodOptions), 2);
    EXPECT_EQ(errorWith({"gravity.self=sweeps", "gravity.sweeps=0"}),
              "--set gravity.sweeps=0: gravity.sweeps: expected a number of sweeps >= 1, got 0");
}

TEST(SceneGravityMethod, OwnKeysUnknownToOtherMethods) {
    // The scene's tree reads no `sweeps`: a typo is never ignored.
    EXPECT_NE(errorWith("gravity.sweeps=5").find("gravity.sweeps"), std::string::npos);
    EXPECT_FALSE(parse({"gravity.self=tree"}).gravity.methodOptions.has_value());
}

TEST(SceneGravityMethod, UnknownNameListsIt) {
    EXPECT_EQ(errorWith("gravity.self=sweep"),
              "--set gravity.self=sweep: gravity.self: expected one of \"none\", \"direct\", "
              "\"tree\", \"pm\", \"p3m\", \"occupied-cells\", \"tree-nodes\", \"mutual-tree\", "
              "\"sweeps\", \"auto\", got \"sweep\" \u2014 did you mean \"sweeps\"?");
}
