// ConfigTable::applyOverride: every form of `--set`, and that values set on the command line
// are reported as coming from the command line.
#include "core/config/ConfigTable.hpp"
#include "tests/core/ConfigTestUtil.hpp"

#include <gtest/gtest.h>

using namespace regolith::core;
using regolith::testing::inputErrorOf;

namespace {

constexpr char const* kScene = R"([domain]
min = [0, 0, 0]
max = [10, 10, 10]
blocks = [1, 1, 1]
[time]
dt = 0.1
[sync]
method = "nns"
[[particles]]
kind = "list"
radius = 1.0
[[particles]]
kind = "lattice"
radius = 0.5
)";

ConfigTable withOverride(std::string_view assignment) {
    auto root = ConfigTable::fromString(kScene, "scene.toml");
    root.applyOverride(assignment);
    return root;
}

} // namespace

TEST(ConfigOverride, NumberReplacesValueAndRemembersItsOrigin) {
    auto const root = withOverride("time.dt=1e-3");
    auto const time = root.table("time");
    EXPECT_EQ(time.get<double>("dt"), 1e-3);
    EXPECT_EQ(time.location("dt"), "--set time.dt=1e-3");
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<int>("dt"); }),
              "--set time.dt=1e-3: time.dt: expected an integer (32 bit), got 0.001 (a number)");
    // Untouched keys keep their file location.
    EXPECT_EQ(root.table("domain").location("max"), "scene.toml:3");
}

TEST(ConfigOverride, BooleansStringsAndBareWords) {
    EXPECT_TRUE(withOverride("sync.reproducible=true").table("sync").getBool("reproducible"));
    EXPECT_EQ(withOverride("sync.method=\"sos\"").table("sync").getString("method"), "sos");
    EXPECT_EQ(withOverride("sync.method=sos").table("sync").getString("method"), "sos");
    EXPECT_EQ(withOverride("contact.model=spring-dashpot").table("contact").getString("model"),
              "spring-dashpot");
    // A bare word that is not a number stays a string, and then fails as a number.
    auto const root = withOverride("time.dt=fast");
    EXPECT_EQ(inputErrorOf([&] { (void)root.table("time").get<double>("dt"); }),
              "--set time.dt=fast: time.dt: expected a number, got \"fast\" (a string)");
    // Bare words TOML would read as a date or a time are strings too (no key takes a date).
    EXPECT_EQ(withOverride("output.dir=2024-05-01").table("output").getString("dir"), "2024-05-01");
    EXPECT_EQ(withOverride("output.dir=07:30:00").table("output").getString("dir"), "07:30:00");
    EXPECT_EQ(withOverride("output.dir=1979-05-27T07:32:00Z").table("output").getString("dir"),
              "1979-05-27T07:32:00Z");
    // Spaces inside a bare value are kept (PETSc options).
    EXPECT_EQ(withOverride("gravity.petsc.options=-pc_type gamg -ksp_rtol 1e-8")
                  .table("gravity")
                  .table("petsc")
                  .getString("options"),
              "-pc_type gamg -ksp_rtol 1e-8");
}

TEST(ConfigOverride, ArraysAndInlineTables) {
    auto const root = withOverride("domain.blocks=[2,2,4]");
    EXPECT_EQ((root.table("domain").getArray<int, 3>("blocks")), (std::array<int, 3>{2, 2, 4}));
    auto const bad = withOverride("domain.blocks=[4, 0, 4]");
    auto const domain = bad.table("domain");
    EXPECT_EQ(inputErrorOf([&] {
                  (void)domain.getIf<std::array<int, 3>>(
                      "blocks", [](auto const& b) { return b[1] > 0; },
                      "an array of 3 positive integers");
              }),
              "--set domain.blocks=[4, 0, 4]: domain.blocks: expected an array of 3 positive "
              "integers, got [4, 0, 4]");
    auto const refined = withOverride("domain.refine=[{min=[0,0,0], max=[1,1,1], level=2}]");
    auto const regions = refined.table("domain").tableArray("refine");
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_EQ(regions[0].get<int>("level"), 2);
    EXPECT_EQ(regions[0].location("level"), "--set domain.refine=[{min=[0,0,0], max=[1,1,1], "
                                            "level=2}]");
}

TEST(ConfigOverride, NestedNewKeysAreCreatedAndThenReportedUnknown) {
    auto const root = withOverride("domain.blokcs=[2,2,2]");
    auto const domain = root.table("domain");
    (void)domain.getVec3("min");
    (void)domain.getVec3("max");
    (void)domain.getOr<std::array<int, 3>>("blocks", {1, 1, 1});
    (void)root.table("time").get<double>("dt");
    (void)root.table("sync").getString("method");
    for (auto const& p : root.tableArray("particles")) {
        (void)p.getString("kind");
        (void)p.get<double>("radius");
    }
    EXPECT_EQ(inputErrorOf([&] { root.rejectUnknownKeys(); }),
              "--set domain.blokcs=[2,2,2]: unknown key 'domain.blokcs' \u2014 did you mean "
              "'blocks'?");

    auto const deep = withOverride("gravity.petsc.options=\"-pc_type lu\"");
    (void)deep.table("domain");
    EXPECT_NE(inputErrorOf([&] {
                  deep.rejectUnknownKeys();
              }).find("--set gravity.petsc.options=\"-pc_type lu\": unknown key 'gravity'"),
              std::string::npos);
}

TEST(ConfigOverride, MissingKeyInATableCreatedByAnOverrideNamesTheFile) {
    auto root = ConfigTable::fromString("[domain]\nmin = [0, 0, 0]\n", "scene.toml");
    root.applyOverride("time.steps=3", "--steps 3");
    auto const time = root.table("time");
    EXPECT_EQ(time.get<int>("steps"), 3);
    EXPECT_EQ(inputErrorOf([&] { (void)time.get<double>("dt"); }),
              "scene.toml: time.dt: required key is missing");
}

TEST(ConfigOverride, IndexedArraysOfTables) {
    auto const a = withOverride("particles.1.radius=0.25");
    EXPECT_EQ(a.tableArray("particles")[1].get<double>("radius"), 0.25);
    EXPECT_EQ(a.tableArray("particles")[0].get<double>("radius"), 1.0);
    auto const b = withOverride("particles[0].radius=2");
    EXPECT_EQ(b.tableArray("particles")[0].get<double>("radius"), 2.0);
    auto const c = withOverride("particles.0.region.min=[1,2,3]");
    EXPECT_EQ(c.tableArray("particles")[0].table("region").getVec3("min"), Vec3(1, 2, 3));
    auto const d = withOverride("particles.1={kind=\"file\", path=\"p.csv\"}");
    EXPECT_EQ(d.tableArray("particles")[1].getString("path"), "p.csv");
}

TEST(ConfigOverride, MalformedAssignmentsAreInputErrors) {
    auto root = ConfigTable::fromString(kScene, "scene.toml");
    auto err = [&](std::string_view a) { return inputErrorOf([&] { root.applyOverride(a); }); };
    EXPECT_EQ(err("time.dt"),
              "--set time.dt: expected section.key=value (e.g. --set time.dt=1e-3)");
    EXPECT_EQ(err("time.dt="), "--set time.dt=: expected section.key=value (e.g. --set "
                               "time.dt=1e-3)");
    EXPECT_EQ(err("=3"), "--set =3: expected section.key=value (e.g. --set time.dt=1e-3)");
    EXPECT_EQ(err("time..dt=3"), "--set time..dt=3: expected section.key=value (e.g. --set "
                                 "time.dt=1e-3)");
    EXPECT_EQ(err("particles.5.radius=1"),
              "--set particles.5.radius=1: 'particles' has 2 entries; '5' is not an index of it");
    EXPECT_EQ(err("particles.x.radius=1"),
              "--set particles.x.radius=1: 'particles' has 2 entries; 'x' is not an index of it");
    EXPECT_EQ(err("time.dt.x=1"), "--set time.dt.x=1: 'time.dt' is a number (written by "
                                  "scene.toml:6), not a table");
    // An entry of an array of tables the scene does not have (it was created as tables named
    // "0", then refused as not an array, showing those tables).
    EXPECT_EQ(err("materials.0.stiffness=5"),
              "--set materials.0.stiffness=5: the scene has no 'materials' entries to take entry "
              "0 of (--set edits the entries a scene file has; add a [[materials]] section to "
              "it)");
    EXPECT_FALSE(root.has("materials"));
    std::string const m = err("domain.blocks=[2,2");
    EXPECT_EQ(m.rfind("--set domain.blocks=[2,2: malformed value '[2,2': ", 0), 0u) << m;
    EXPECT_EQ(err("sync.method=\"sos").rfind("--set sync.method=\"sos: malformed value", 0), 0u);
    EXPECT_EQ(err("time.dt=1\nsteps=3").rfind("--set time.dt=1\nsteps=3: ", 0), 0u);
    // Nothing above changed the document.
    EXPECT_EQ(root.table("time").get<double>("dt"), 0.1);
    // The blocking value came from another option: it is named (the message blamed only the
    // option that ran into it, e.g. --steps after --set time=3).
    root.applyOverride("time=3");
    EXPECT_EQ(inputErrorOf([&] { root.applyOverride("time.steps=3", "--steps 3"); }),
              "--steps 3: 'time' is an integer (written by --set time=3), not a table");
}

TEST(ConfigOverride, LaterOverridesWinAndCustomOriginsAreReported) {
    auto root = ConfigTable::fromString(kScene, "scene.toml");
    root.applyOverride("time.steps=5");
    root.applyOverride("time.steps=-7", "--steps -7");
    auto const time = root.table("time");
    EXPECT_EQ(time.get<int>("steps"), -7);
    EXPECT_EQ(inputErrorOf([&] {
                  (void)time.getIf<int>(
                      "steps", [](int s) { return s >= 0; }, "a non-negative integer");
              }),
              "--steps -7: time.steps: expected a non-negative integer, got -7");
}
