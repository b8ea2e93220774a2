// Scene sections: the default scene parses to what it says; every validation rule of every
// section rejects a bad value with a message naming where it came from. [[particles]] entries
// are read into the generators' particles::ParticleSpec; their value rules are the generators'
// (validateParticleSpecs), reported with the scene location.
#include "apps/regolith/SceneSections.hpp"

#include "apps/regolith/SceneKeyLocation.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <variant>

using namespace regolith;
using apps::SceneDescription;

namespace {

// A valid scene using every section; the tests break it one key at a time with --set.
constexpr char const* kScene = R"([domain]
min = [0, 0, 0]
max = [8, 8, 4]
blocks = [2, 2, 1]
periodic = [true, false, false]
refine = [{ min = [0, 0, 0], max = [2, 2, 2], level = 1 }]
cells_per_block = [8, 8, 8]
[time]
dt = 0.01
steps = 10
[sync]
method = "sos"
[contact]
model = "hertz"
stiffness = 1e7
restitution = 0.5
friction = 0.3
rolling_friction = 0.01
[gravity]
external = [0, 0, -9.81]
self = "tree"
G = 1.0
theta = 0.7
update_threshold = 0.1
softening = 0.01
[gravity.petsc]
options = "-pc_type gamg"
[[particles]]
kind = "lattice"
lattice = "hcp"
spacing = 1.0
radius = 0.5
density = 2.0
velocity = { random = [-0.1, 0.1], seed = 7 }
[[particles]]
kind = "list"
radius = [1.0, 2.0]
position = [[1, 1, 1], [5, 5, 2]]
density = 3.0
[[particles]]
kind = "agglomerate"
center = [4, 4, 2]
radius = 1.5
grain_radius = [0.1, 0.2]
count = 100
velocity = [0, 1, 0]
density = 3000.0
seed = 3
[[particles]]
kind = "file"
path = "initial.csv"
density = 2.5
type = 2
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 2]
type = 1
[output]
dir = "results"
vtk_every = 10
checkpoint_every = 100
)";

SceneDescription parse(std::initializer_list<std::string_view> overrides = {}) {
    auto root = core::ConfigTable::fromString(kScene, "scenes/s.toml");
    for (auto const o : overrides)
        root.applyOverride(o);
    return apps::parseScene(root, "scenes/s.toml");
}

/// The InputError message for the scene with `override` applied.
std::string errorWith(std::string_view override) {
    try {
        (void)parse({override});
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(SceneSections, EverySectionParsed) {
    auto const s = parse();
    EXPECT_EQ(s.name, "s");
    EXPECT_EQ(s.forest.domain.max, core::Vec3(8, 8, 4));
    EXPECT_EQ(s.forest.rootBlocks, (std::array<int, 3>{2, 2, 1}));
    EXPECT_EQ(s.forest.periodic, (std::array<bool, 3>{true, false, false}));
    ASSERT_EQ(s.forest.refine.size(), 1u);
    EXPECT_EQ(s.forest.refine[0].level, 1);
    EXPECT_EQ(s.forest.cellsPerBlock, (std::array<int, 3>{8, 8, 8}));
    EXPECT_EQ(s.time.dt, 0.01);
    EXPECT_EQ(s.time.steps, 10);
    EXPECT_EQ(s.time.integrator, apps::Integrator::Verlet);
    EXPECT_TRUE(s.time.orientation); // the default
    EXPECT_FALSE(parse({"time.orientation=false"}).time.orientation);
    EXPECT_EQ(s.sync.method, particles::SyncMethod::ShadowOwner);
    EXPECT_FALSE(s.sync.reproducible); // the default
    EXPECT_TRUE(parse({"sync.reproducible=true"}).sync.reproducible);
    EXPECT_EQ(s.contact.model, apps::ContactModel::Hertz);
    EXPECT_EQ(s.contact.rollingFriction, 0.01);
    EXPECT_EQ(s.gravity.self, apps::SelfGravity::Tree);
    EXPECT_EQ(s.gravity.external, core::Vec3(0, 0, -9.81));
    EXPECT_EQ(s.gravity.petscOptions, "-pc_type gamg");
    ASSERT_EQ(s.particles.size(), 4u);
    auto const& lattice = std::get<particles::LatticeSpec>(s.particles[0].kind);
    EXPECT_EQ(lattice.lattice, particles::LatticeKind::HexagonalClosePacked);
    EXPECT_EQ(lattice.spacing, 1.0);
    EXPECT_EQ(lattice.density, 2.0);
    EXPECT_EQ(lattice.region.min, s.forest.domain.min); // default region: the domain
    EXPECT_EQ(lattice.region.max, s.forest.domain.max);
    auto const& random = std::get<particles::RandomVelocity>(lattice.velocity);
    EXPECT_EQ(random.lo, -0.1);
    EXPECT_EQ(random.hi, 0.1);
    EXPECT_EQ(random.seed, 7u);
    EXPECT_EQ(s.particles[0].type, 0u);
    auto const& list = std::get<particles::ListSpec>(s.particles[1].kind);
    EXPECT_EQ(list.radius, (std::vector<double>{1.0, 2.0}));
    EXPECT_EQ(list.position[1], core::Vec3(5, 5, 2));
    EXPECT_TRUE(list.velocity.empty()); // at rest
    EXPECT_EQ(list.density, 3.0);
    auto const& agg = std::get<particles::AgglomerateSpec>(s.particles[2].kind);
    EXPECT_EQ(agg.center, core::Vec3(4, 4, 2));
    EXPECT_EQ(agg.count, 100);
    EXPECT_EQ(agg.velocity, core::Vec3(0, 1, 0));
    EXPECT_EQ(agg.grainRadiusMin, 0.1);
    EXPECT_EQ(agg.grainRadiusMax, 0.2);
    EXPECT_EQ(agg.seed, 3u);
    EXPECT_EQ(agg.maxAttempts, particles::AgglomerateSpec{}.maxAttempts);
    auto const& file = std::get<particles::FileSpec>(s.particles[3].kind);
    EXPECT_EQ(file.path, "scenes/initial.csv"); // relative to the scene file
    EXPECT_EQ(file.density, 2.5);
    EXPECT_EQ(s.particles[3].type, 2u);
    ASSERT_EQ(s.walls.size(), 1u);
    EXPECT_EQ(s.walls[0].normal, core::Vec3(0, 0, 1)); // normalised
    EXPECT_EQ(s.walls[0].type, 1u);
    EXPECT_EQ(s.walls[0].uid, particles::wallUid(0));
    EXPECT_EQ(s.output.dir, "results");
    EXPECT_EQ(s.output.checkpointEvery, 100);
}

TEST(SceneSections, DefaultsForOptionalSections) {
    auto const root = core::ConfigTable::fromString(
        "[domain]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n[time]\ndt = 1\nsteps = 0\n", "m.toml");
    auto const s = apps::parseScene(root, "");
    EXPECT_EQ(s.name, "default");
    EXPECT_EQ(s.forest.rootBlocks, (std::array<int, 3>{1, 1, 1}));
    EXPECT_EQ(s.sync.method, particles::SyncMethod::Hybrid); // the scenes' default
    EXPECT_FALSE(s.sync.reproducible);
    EXPECT_EQ(s.contact.model, apps::ContactModel::SpringDashpot);
    EXPECT_EQ(s.contact.stiffness, 1e4);
    EXPECT_EQ(s.gravity.self, apps::SelfGravity::None);
    EXPECT_TRUE(s.particles.empty());
    EXPECT_EQ(s.output.dir, "out");
}

TEST(SceneSections, DefaultSceneFileIsValid) {
    auto const root = core::ConfigTable::fromFile(REGOLITH_SOURCE_DIR "/scenes/default.toml");
    auto const s = apps::parseScene(root, "scenes/default.toml");
    EXPECT_EQ(s.name, "rubble-piles-merge");
    EXPECT_EQ(s.forest.rootBlocks, (std::array<int, 3>{4, 3, 2}));
    EXPECT_EQ(s.sync.method, particles::SyncMethod::Hybrid);
    // The coupled default leaves the gravity method, its update threshold and dt to the driver.
    EXPECT_EQ(s.gravity.self, apps::SelfGravity::Auto);
    EXPECT_TRUE(s.gravity.thresholdAuto);
    EXPECT_TRUE(s.time.dtAuto);
    EXPECT_GT(s.output.vtkEvery, 0);
    ASSERT_EQ(s.particles.size(), 2u);
    for (auto const& pile : s.particles)
        EXPECT_EQ(std::get<particles::AgglomerateSpec>(pile.kind).count, 1200);
}

TEST(SceneSections, DomainRules) {
    EXPECT_EQ(errorWith("domain.blocks=[4,0,4]"),
              "--set domain.blocks=[4,0,4]: domain.blocks: expected an array of 3 positive "
              "integers (at most 2097152 each), got [4, 0, 4]");
    EXPECT_EQ(errorWith("domain.balance=grains"),
              "--set domain.balance=grains: domain.balance: expected one of \"load\", "
              "\"blocks\", got \"grains\"");
    EXPECT_EQ(errorWith("domain.cell_weight=-1"),
              "--set domain.cell_weight=-1: domain.cell_weight: expected a non-negative finite "
              "number, got -1");
    EXPECT_EQ(errorWith("domain.max=[8,-1,4]"),
              "--set domain.max=[8,-1,4]: domain.max: must exceed domain.min on every axis, got "
              "min = [0, 0, 0], max = [8, -1, 4]");
    EXPECT_EQ(errorWith("domain.min=[0,0,nan]"),
              "--set domain.min=[0,0,nan]: domain.min: expected an array of 3 finite numbers, got "
              "[0, 0, nan]");
    EXPECT_EQ(errorWith("domain.cells_per_block=[8,0,8]"),
              "--set domain.cells_per_block=[8,0,8]: domain.cells_per_block: expected an array of "
              "3 integers, all positive (or all zero: no grid), got [8, 0, 8]");
    EXPECT_EQ(errorWith("domain.refine.0.level=9"),
              "--set domain.refine.0.level=9: domain.refine[0].level: expected an integer in [0, "
              "8], got 9");
    EXPECT_EQ(errorWith("domain.refine.0.max=[2,2,9]"),
              "--set domain.refine.0.max=[2,2,9]: domain.refine[0].max: the region [0, 0, 0] - "
              "[2, 2, 9] must lie inside the domain [0, 0, 0] - [8, 8, 4]");
    EXPECT_EQ(errorWith("domain.refine.0.min=[3,0,0]"),
              "scenes/s.toml:6: domain.refine[0].max: must not be below "
              "domain.refine[0].min on any axis, got min = [3, 0, 0], max = [2, 2, 2]");
    EXPECT_EQ(errorWith("domain.periodic=[true,false]"),
              "--set domain.periodic=[true,false]: domain.periodic: expected an array of 3 "
              "booleans, got [true, false]");
}

TEST(SceneSections, TimeSyncContactGravityOutputRules) {
    EXPECT_EQ(errorWith("time.dt=0"), "--set time.dt=0: time.dt: expected a positive finite "
                                      "number or \"auto\", got 0");
    EXPECT_EQ(errorWith("time.dt=inf"), "--set time.dt=inf: time.dt: expected a positive finite "
                                        "number or \"auto\", got inf");
    EXPECT_EQ(errorWith("time.steps=-1"), "--set time.steps=-1: time.steps: expected a "
                                          "non-negative integer, got -1");
    EXPECT_EQ(errorWith("time.integrator=leapfrog"),
              "--set time.integrator=leapfrog: time.integrator: expected one of \"euler\", "
              "\"verlet\", got \"leapfrog\"");
    EXPECT_EQ(errorWith("time.allow_unstable=1"),
              "--set time.allow_unstable=1: time.allow_unstable: expected a boolean, got 1 (an "
              "integer)");
    EXPECT_EQ(errorWith("time.orientation=0"),
              "--set time.orientation=0: time.orientation: expected a boolean, got 0 (an "
              "integer)");
    EXPECT_EQ(errorWith("sync.method=sso"),
              "--set sync.method=sso: sync.method: expected one of \"nns\", \"sos\", \"hybrid\", "
              "got \"sso\" \u2014 did you mean \"sos\"?");
    EXPECT_EQ(errorWith("sync.method=nns"), "(no error)");
    EXPECT_EQ(errorWith("sync.reproducible=yes"),
              "--set sync.reproducible=yes: sync.reproducible: expected a boolean, got \"yes\" "
              "(a string)");
    EXPECT_EQ(errorWith("sync.reproducable=true"),
              "--set sync.reproducable=true: unknown key 'sync.reproducable' \u2014 did you mean "
              "'reproducible'?");
    EXPECT_EQ(errorWith("contact.model=hooke"),
              "--set contact.model=hooke: contact.model: expected one of \"spring-dashpot\", "
              "\"hertz\", got \"hooke\"");
    EXPECT_EQ(errorWith("contact.restitution=1.5"),
              "--set contact.restitution=1.5: contact.restitution: expected a number in (0, 1], "
              "got 1.5");
    EXPECT_EQ(errorWith("contact.friction=-0.1"),
              "--set contact.friction=-0.1: contact.friction: expected a non-negative finite "
              "number, got -0.1");
    EXPECT_EQ(errorWith("contact.stiffness=0"),
              "--set contact.stiffness=0: contact.stiffness: expected a positive finite number, "
              "got 0");
    EXPECT_EQ(errorWith("gravity.self=occupied_cells"),
              "--set gravity.self=occupied_cells: gravity.self: expected one of \"none\", "
              "\"direct\", \"tree\", \"pm\", \"p3m\", \"occupied-cells\", \"tree-nodes\", "
              "\"mutual-tree\", \"auto\", got \"occupied_cells\" \u2014 did you mean "
              "\"occupied-cells\"?");
    EXPECT_EQ(errorWith("gravity.theta=0"),
              "--set gravity.theta=0: gravity.theta: expected a positive finite number, got 0");
    EXPECT_EQ(errorWith("gravity.G=-1"),
              "--set gravity.G=-1: gravity.G: expected a positive finite number, got -1");
    EXPECT_EQ(errorWith("gravity.petsc.options=3"),
              "--set gravity.petsc.options=3: gravity.petsc.options: expected a string, got 3 (an "
              "integer)");
    EXPECT_EQ(errorWith("output.vtk_every=-2"),
              "--set output.vtk_every=-2: output.vtk_every: expected a non-negative integer, got "
              "-2");
    EXPECT_EQ(errorWith("walls.0.normal=[0,0,0]"),
              "--set walls.0.normal=[0,0,0]: walls[0].normal: expected a non-zero vector of 3 "
              "finite numbers, got [0, 0, 0]");
}

TEST(SceneSections, ParticleTomlRules) {
    EXPECT_EQ(errorWith("particles.0.kind=lattise"),
              "--set particles.0.kind=lattise: particles[0].kind: expected one of \"lattice\", "
              "\"list\", \"agglomerate\", \"file\", got \"lattise\" \u2014 did you mean "
              "\"lattice\"?");
    // sc and hcp are the generators' lattices.
    EXPECT_EQ(errorWith("particles.0.lattice=fcc"),
              "--set particles.0.lattice=fcc: particles[0].lattice: expected one of \"sc\", "
              "\"hcp\", got \"fcc\"");
    EXPECT_EQ(errorWith("particles.0.spacing=\"wide\""),
              "--set particles.0.spacing=\"wide\": particles[0].spacing: expected a number, got "
              "\"wide\" (a string)");
    EXPECT_EQ(errorWith("particles.0.velocity=7"),
              "--set particles.0.velocity=7: particles[0].velocity: expected [vx, vy, vz] or a "
              "table { random = [lo, hi], seed = n }, got 7");
    EXPECT_EQ(errorWith("particles.0.velocity.seed=-1"),
              "--set particles.0.velocity.seed=-1: particles[0].velocity.seed: expected a "
              "non-negative integer, got -1");
    EXPECT_EQ(errorWith("particles.1.radius=[1.0,\"x\"]"),
              "--set particles.1.radius=[1.0,\"x\"]: particles[1].radius: expected an array of "
              "numbers, got [1, \"x\"]");
    EXPECT_EQ(errorWith("particles.2.count=1.5"),
              "--set particles.2.count=1.5: particles[2].count: expected an integer, got 1.5 (a "
              "number)");
    EXPECT_EQ(errorWith("particles.3.type=-1"),
              "--set particles.3.type=-1: particles[3].type: expected a material index (an "
              "integer in [0, 4294967295]), got -1");
    EXPECT_EQ(errorWith("walls.0.type=4294967296"),
              "--set walls.0.type=4294967296: walls[0].type: expected a material index (an "
              "integer in [0, 4294967295]), got 4294967296");
}

TEST(SceneSections, ParticleValueRulesAreTheGenerators) {
    EXPECT_EQ(errorWith("particles.0.density=0"),
              "--set particles.0.density=0: particles[0].density: must be positive, got 0");
    EXPECT_EQ(errorWith("particles.1.radius=[1.0,1.0,1.0]"),
              "--set particles.1.radius=[1.0,1.0,1.0]: particles[1].radius: expected 1 value or "
              "one per position (2), got 3");
    EXPECT_EQ(errorWith("particles.1.radius=-2"),
              "--set particles.1.radius=-2: particles[1].radius[0]: must be positive, got -2");
    EXPECT_EQ(errorWith("particles.0.velocity.random=[1,-1]"),
              "--set particles.0.velocity.random=[1,-1]: particles[0].velocity.random: expected "
              "[lo, hi] with lo <= hi, both finite, got [1, -1]");
    EXPECT_EQ(errorWith("particles.2.grain_radius=[0.1,2.0]"),
              "--set particles.2.grain_radius=[0.1,2.0]: particles[2].grain_radius: max (2) must "
              "be below the agglomerate radius (1.5)");
    EXPECT_EQ(errorWith("particles.2.max_attempts=0"),
              "--set particles.2.max_attempts=0: particles[2].max_attempts: must be >= 1, got 0");
    EXPECT_EQ(errorWith("particles.3.path=\"\""),
              "--set particles.3.path=\"\": particles[3].path: must name a CSV file, got an "
              "empty string");
    EXPECT_EQ(errorWith("particles.3.density=-1"),
              "--set particles.3.density=-1: particles[3].density: must be positive, got -1");
    // A key written in the file gets the file's line; an absent key its table's.
    auto const root = core::ConfigTable::fromString(
        "[domain]\nmin = [0, 0, 0]\nmax = [4, 4, 4]\n[time]\ndt = 1\nsteps = 0\n"
        "[[particles]]\nkind = \"list\"\nposition = [[1, 1, 1], [9, 1, 1]]\nradius = 0.5\n"
        "density = 1\n",
        "l.toml");
    try {
        (void)apps::parseScene(root, "l.toml");
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_STREQ(e.what(), "l.toml:9: particles[0].position[1]: centre [9, 1, 1] lies outside "
                               "the domain (min = [0, 0, 0], max = [4, 4, 4])");
    }
}

TEST(SceneSections, OverlappingLatticeIsAccepted) {
    // MESA-PD's GranularGas geometry: sc spacing 1, radius 0.6, neighbours overlap.
    auto const s = parse({"particles.0.lattice=sc", "particles.0.radius=0.6"});
    EXPECT_EQ(std::get<particles::LatticeSpec>(s.particles[0].kind).radius, 0.6);
}

TEST(SceneSections, VelocityForms) {
    auto const s = parse({"particles.0.velocity=[1,2,3]", "particles.1.velocity=[0,0,-1]"});
    EXPECT_EQ(std::get<core::Vec3>(std::get<particles::LatticeSpec>(s.particles[0].kind).velocity),
              core::Vec3(1, 2, 3));
    EXPECT_EQ(std::get<particles::ListSpec>(s.particles[1].kind).velocity,
              (std::vector<core::Vec3>{core::Vec3(0, 0, -1)})); // one for every grain
    auto const t = parse({"particles.1.velocity=[[1,0,0],[0,1,0]]", "particles.2.grain_radius=0.2",
                          "particles.2.max_attempts=50"});
    EXPECT_EQ(std::get<particles::ListSpec>(t.particles[1].kind).velocity.size(), 2u);
    auto const& agg = std::get<particles::AgglomerateSpec>(t.particles[2].kind);
    EXPECT_EQ(agg.grainRadiusMin, 0.2);
    EXPECT_EQ(agg.grainRadiusMax, 0.2);
    EXPECT_EQ(agg.maxAttempts, 50);
}

TEST(SceneSections, TyposAnywhereAreRejectedAfterParsing) {
    EXPECT_EQ(errorWith("particles.2.sead=3"),
              "--set particles.2.sead=3: unknown key 'particles[2].sead' \u2014 did you mean "
              "'seed'?");
    EXPECT_EQ(errorWith("particles.1.spacing=1.0"),
              "--set particles.1.spacing=1.0: unknown key 'particles[1].spacing' (known keys "
              "here: density, kind, position, radius, type, velocity)");
    EXPECT_EQ(errorWith("gravity.petsc.option=\"-ksp_view\""),
              "--set gravity.petsc.option=\"-ksp_view\": unknown key 'gravity.petsc.option' "
              "\u2014 did you mean 'options'?");
    EXPECT_EQ(errorWith("outptu.dir=\"x\""),
              "--set outptu.dir=\"x\": unknown key 'outptu' \u2014 did you mean 'output'?");
    // In a file, the message names the line.
    auto const root = core::ConfigTable::fromString(
        "[domain]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n[time]\ndt = 1\nsteps = 0\nstesp = 3\n",
        "t.toml");
    try {
        (void)apps::parseScene(root, "t.toml");
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_STREQ(e.what(), "t.toml:7: unknown key 'time.stesp' \u2014 did you mean 'steps'?");
    }
}

TEST(SceneKeyLocation, DeepestWrittenKeyOfTheNamedEntry) {
    auto const root = core::ConfigTable::fromString(kScene, "s.toml");
    auto const at = [&](std::string_view m) { return apps::locateSceneKey(root, m); };
    // particles[0] starts on line 28 of kScene; its velocity table is written inline on 34.
    EXPECT_EQ(at("particles[0].spacing: must be positive, got 0"),
              "s.toml:31: particles[0].spacing: must be positive, got 0");
    EXPECT_EQ(at("particles[0].velocity.random: bad"),
              "s.toml:34: particles[0].velocity.random: bad");
    EXPECT_EQ(at("particles[1].position[1]: outside"),
              "s.toml:38: particles[1].position[1]: outside");
    // A key the entry does not have: the entry's own line.
    EXPECT_EQ(at("particles[0].region: outside"), "s.toml:28: particles[0].region: outside");
    EXPECT_EQ(at("particles[2]: cannot pack"), "s.toml:40: particles[2]: cannot pack");
    EXPECT_EQ(at("walls[0].normal: zero"), "s.toml:56: walls[0].normal: zero");
    // Not an entry of this scene, or not a key: unchanged.
    EXPECT_EQ(at("particles[9].radius: bad"), "particles[9].radius: bad");
    EXPECT_EQ(at("particles: too many entries"), "particles: too many entries");
    EXPECT_EQ(at("particles[x].radius: bad"), "particles[x].radius: bad");
    EXPECT_EQ(at("no key here"), "no key here");
}
