// Scene sections: a scene using every section, and the default scene, parse to what they say;
// optional sections take their defaults; velocity forms; where a key came from
// (SceneKeyLocation). The validation rules are in SceneRulesTest.cpp.
#include "apps/regolith/SceneSections.hpp"

#include "apps/regolith/SceneKeyLocation.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"
#include "tests/apps/SceneFixture.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <variant>

using namespace regolith;
using apps::SceneDescription;
using namespace regolith::apps::test;

TEST(SceneSections, EverySectionParsed) {
    auto const s = parse();
    EXPECT_EQ(s.name, "s");
    EXPECT_EQ(s.forest.domain.max, core::Vec3(8, 8, 4));
    EXPECT_EQ(s.forest.rootBlocks, (std::array<int, 3>{2, 2, 1}));
    EXPECT_EQ(s.forest.periodic, (std::array<bool, 3>{false, false, false}));
    ASSERT_EQ(s.forest.refine.size(), 1u);
    EXPECT_EQ(s.forest.refine[0].level, 1);
    EXPECT_EQ(s.forest.cellsPerBlock, (std::array<int, 3>{8, 8, 8}));
    EXPECT_EQ(s.time.dt, 0.01);
    EXPECT_EQ(s.time.steps, 10);
    EXPECT_EQ(s.time.integrator, apps::Integrator::Verlet);
    EXPECT_TRUE(s.time.orientationAuto); // the default: resolveSpeedChoices decides
    EXPECT_FALSE(parse({"time.orientation=false"}).time.orientation);
    EXPECT_FALSE(parse({"time.orientation=false"}).time.orientationAuto);
    EXPECT_TRUE(parse({"time.orientation=\"auto\""}).time.orientationAuto);
    EXPECT_EQ(s.sync.method, particles::SyncMethod::ShadowOwner);
    EXPECT_TRUE(s.sync.skinAuto);                                // the default
    EXPECT_EQ(s.sync.subdomains, domain::Subdomains::RankBoxes); // the default
    EXPECT_EQ(parse({"sync.subdomains=\"blocks\""}).sync.subdomains, domain::Subdomains::Blocks);
    apps::SyncSection const skin = parse({"sync.method=\"hybrid\"", "sync.skin=0.2"}).sync;
    EXPECT_FALSE(skin.skinAuto);
    EXPECT_EQ(skin.skin, 0.2);
    EXPECT_FALSE(s.sync.reproducible); // the default
    EXPECT_TRUE(parse({"sync.reproducible=true"}).sync.reproducible);
    EXPECT_EQ(s.contact.model, "hertz");
    EXPECT_EQ(s.materials.of(0).rollingFriction, 0.01);
    EXPECT_EQ(s.materials.of(0).youngsModulus, 1.82e7);
    EXPECT_EQ(s.materials.of(0).poissonRatio, 0.3);
    EXPECT_FALSE(s.contact.rollingSpring.enabled); // the default: model A
    auto const c = parse({"contact.rolling_model=\"spring\"", "contact.rolling_stiffness=40",
                          "contact.rolling_damping_ratio=0.5"})
                       .contact.rollingSpring;
    EXPECT_TRUE(c.enabled);
    EXPECT_EQ(c.stiffness, 40.0);
    EXPECT_EQ(c.dampingRatio, 0.5);
    EXPECT_FALSE(s.contact.neighbourSkin); // the default: relative to the radius
    EXPECT_EQ(parse({"contact.neighbour_skin=0.2"}).contact.neighbourSkin, 0.2);
    EXPECT_EQ(parse({"contact.neighbour_skin=0"}).contact.neighbourSkin, 0.0);
    EXPECT_EQ(s.gravity.self, "tree");
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
    EXPECT_EQ(s.walls[0].geometry.normal, core::Vec3(0, 0, 1)); // normalised
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
    EXPECT_EQ(s.contact.model, "spring-dashpot");
    EXPECT_EQ(s.materials.of(0).stiffness, 1e4);
    EXPECT_EQ(s.gravity.self, "none");
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
    EXPECT_EQ(s.gravity.self, "auto");
    EXPECT_TRUE(s.gravity.thresholdAuto);
    EXPECT_TRUE(s.time.dtAuto);
    EXPECT_GT(s.output.vtkEvery, 0);
    ASSERT_EQ(s.particles.size(), 2u);
    for (auto const& pile : s.particles)
        EXPECT_EQ(std::get<particles::AgglomerateSpec>(pile.kind).count, 1200);
}

TEST(SceneSections, OverlappingLatticeIsAccepted) {
    // MESA-PD's GranularGas geometry: sc spacing 1, radius 0.6, neighbours overlap by a
    // third of the radius, which contact.initial_overlap must allow; refused at parse time
    // otherwise (a spacing far below the diameter generated more grains than memory holds
    // before the overlap check refused them).
    auto const s =
        parse({"particles.0.lattice=sc", "particles.0.radius=0.6", "contact.initial_overlap=0.34"});
    EXPECT_EQ(std::get<particles::LatticeSpec>(s.particles[0].kind).radius, 0.6);
    try {
        (void)parse({"particles.0.lattice=sc", "particles.0.radius=0.6"});
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "particles[0].spacing: grains of radius 0.6 at spacing 1 overlap their "
                      "neighbours by 0.2, more than contact.initial_overlap"),
                  std::string::npos)
            << e.what();
    }
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

TEST(SceneKeyLocation, DeepestWrittenKeyOfTheNamedEntry) {
    auto const root = core::ConfigTable::fromString(kScene, "s.toml");
    auto const at = [&](std::string_view m) { return apps::locateSceneKey(root, m); };
    // particles[0] starts on line 28 of kScene; its velocity table is written inline on 34.
    EXPECT_EQ(at("particles[0].spacing: must be positive, got 0"),
              "s.toml:32: particles[0].spacing: must be positive, got 0");
    EXPECT_EQ(at("particles[0].velocity.random: bad"),
              "s.toml:35: particles[0].velocity.random: bad");
    EXPECT_EQ(at("particles[1].position[1]: outside"),
              "s.toml:39: particles[1].position[1]: outside");
    // A key the entry does not have: the entry's own line.
    EXPECT_EQ(at("particles[0].region: outside"), "s.toml:29: particles[0].region: outside");
    EXPECT_EQ(at("particles[2]: cannot pack"), "s.toml:41: particles[2]: cannot pack");
    EXPECT_EQ(at("walls[0].normal: zero"), "s.toml:57: walls[0].normal: zero");
    // Not an entry of this scene, or not a key: unchanged.
    EXPECT_EQ(at("particles[9].radius: bad"), "particles[9].radius: bad");
    EXPECT_EQ(at("particles: too many entries"), "particles: too many entries");
    EXPECT_EQ(at("particles[x].radius: bad"), "particles[x].radius: bad");
    EXPECT_EQ(at("no key here"), "no key here");
}
