// Scene sections: every validation rule of every section rejects a bad value with a message
// naming where it came from. [[particles]] entries are read into the generators'
// particles::ParticleSpec; their value rules are the generators' (validateParticleSpecs),
// reported with the scene location.
#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "tests/apps/SceneFixture.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <variant>

using namespace regolith;
using apps::SceneDescription;
using namespace regolith::apps::test;

TEST(SceneSections, DomainRules) {
    EXPECT_EQ(errorWith("domain.blocks=[4,0,4]"),
              "--set domain.blocks=[4,0,4]: domain.blocks: expected an array of 3 positive "
              "integers (at most 2097152 each), got [4, 0, 4]");
    // Beyond int: the limit, not "expected integers".
    EXPECT_EQ(errorWith("domain.blocks=[9223372036854775807,1,1]"),
              "--set domain.blocks=[9223372036854775807,1,1]: domain.blocks: expected an array of "
              "3 positive integers (at most 2097152 each), got [9223372036854775807, 1, 1]");
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
              "--set time.orientation=0: time.orientation: expected true, false or \"auto\", "
              "got 0");
    EXPECT_EQ(errorWith("sync.skin=true"),
              "--set sync.skin=true: sync.skin: expected a non-negative finite length or "
              "\"auto\", got true");
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
              "\"hertz\", \"vdw\", \"dmt\", got \"hooke\"");
    EXPECT_EQ(errorWith("contact.restitution=1.5"),
              "--set contact.restitution=1.5: contact.restitution: expected a number in (0, 1], "
              "got 1.5");
    EXPECT_EQ(errorWith("contact.rolling_model=sds"),
              "--set contact.rolling_model=sds: contact.rolling_model: expected one of "
              "\"constant\", \"spring\", got \"sds\"");
    EXPECT_EQ(errorWith("contact.rolling_stiffness=10"),
              "--set contact.rolling_stiffness=10: contact.rolling_stiffness: applies only with "
              "rolling_model = \"spring\" (model C)");
    EXPECT_EQ(errorWith({"contact.rolling_damping_ratio=-1", "contact.rolling_model=spring"}),
              "--set contact.rolling_damping_ratio=-1: contact.rolling_damping_ratio: expected a "
              "non-negative finite number, got -1");
    EXPECT_EQ(errorWith({"contact.rolling_model=spring", "contact.rolling_stiffness=5"}),
              "(no error)");
    EXPECT_EQ(errorWith("contact.friction=-0.1"),
              "--set contact.friction=-0.1: contact.friction: expected a non-negative finite "
              "number, got -0.1");
    EXPECT_EQ(errorWith("contact.youngs_modulus=0"),
              "--set contact.youngs_modulus=0: contact.youngs_modulus: expected a positive finite "
              "Young's modulus (a pressure), required with contact.model = \"hertz\", got 0");
    EXPECT_EQ(errorWith("gravity.self=occupied_cells"),
              "--set gravity.self=occupied_cells: gravity.self: expected one of \"none\", "
              "\"direct\", \"tree\", \"pm\", \"p3m\", \"occupied-cells\", \"tree-nodes\", "
              "\"mutual-tree\", \"auto\", got \"occupied_cells\" \u2014 did you mean "
              "\"occupied-cells\"?");
    // The sums over grains have no periodic images (the grid methods refuse a mixed one).
    EXPECT_EQ(errorWith("domain.periodic=[false,true,true]"),
              "scenes/s.toml:22: gravity.self: \"tree\" sums the grains' gravity in free space, "
              "without periodic images, but domain.periodic makes y, z periodic (grains across a "
              "periodic face would attract each other through the whole domain); use \"pm\" or "
              "\"p3m\" with every axis periodic, or an open domain");
    EXPECT_EQ(errorWith({"domain.periodic=[true,false,false]", "gravity.self=pm"}), "(no error)");
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
              "numbers, got [1.0, \"x\"]");
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

TEST(SceneSections, TyposAnywhereAreRejectedAfterParsing) {
    EXPECT_EQ(errorWith("particles.2.sead=3"),
              "--set particles.2.sead=3: unknown key 'particles[2].sead' \u2014 did you mean "
              "'seed'?");
    EXPECT_EQ(errorWith("particles.1.spacing=1.0"),
              "--set particles.1.spacing=1.0: unknown key 'particles[1].spacing' (known keys "
              "here: angular_velocity, density, fixed, kind, position, radius, type, velocity)");
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

TEST(SceneSections, CohesiveContactModelRules) {
    // Each cohesive model's own keys, checked by its registry entry, named in the message.
    std::string_view const vdw = "contact.model=vdw";
    EXPECT_EQ(errorWith({vdw, "contact.hamaker=-1e-20", "contact.min_separation=1e-3",
                         "contact.cutoff=0.1"}),
              "--set contact.hamaker=-1e-20: contact.hamaker: expected a positive Hamaker "
              "constant A (an energy) (required with contact.model = \"vdw\"), got -1e-20");
    EXPECT_EQ(errorWith({vdw, "contact.hamaker=1e-3", "contact.min_separation=0.01",
                         "contact.cutoff=0.005"}),
              "--set contact.cutoff=0.005: contact.cutoff: expected a cut-off gap (a length) "
              "above min_separation = 0.01 (required with contact.model = \"vdw\"), got 0.005");
    EXPECT_EQ(
        errorWith({vdw, "contact.hamaker=1e-3", "contact.min_separation=0", "contact.cutoff=0.1"}),
        "--set contact.min_separation=0: contact.min_separation: expected a positive "
        "minimum separation (a length, where the force stops growing) (required with "
        "contact.model = \"vdw\"), got 0");
    EXPECT_NE(errorWith({vdw, "contact.min_separation=0.01", "contact.cutoff=0.1"})
                  .find("contact.hamaker"),
              std::string::npos);
    EXPECT_EQ(errorWith({"contact.model=dmt", "contact.surface_energy=-0.5"}),
              "--set contact.surface_energy=-0.5: contact.surface_energy: expected a "
              "non-negative surface energy gamma (energy / area; the pull-off force is 2 pi "
              "gamma R*), required with contact.model = \"dmt\", got -0.5");
    // The model's keys are no typo for it (the scene's materials are Hertz's, as dmt's), and
    // stand refused for the others.
    EXPECT_EQ(errorWith({"contact.model=dmt", "contact.surface_energy=0.5"}), "(no error)");
    EXPECT_NE(errorWith("contact.hamaker=1e-3").find("unknown key 'contact.hamaker'"),
              std::string::npos);
}
