// Every invalid [[particles]] entry is a core::InputError whose message names the entry and
// the key ("particles[1].spacing: must be positive, got 0").
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

core::AABB const kDomain = box(Vec3::Zero(), Vec3(10, 10, 10));
double const kNan = std::numeric_limits<double>::quiet_NaN();

struct Case {
    std::string name;
    std::function<void(ParticleSpec&)> mutate; ///< applied to entry 1
    ParticleSpec base;
    std::string expected; ///< substring of the message
    Periodic periodic{false, false, false};
};

LatticeSpec& asLattice(ParticleSpec& s) {
    return std::get<LatticeSpec>(s.kind);
}
ListSpec& asList(ParticleSpec& s) {
    return std::get<ListSpec>(s.kind);
}
AgglomerateSpec& asAgg(ParticleSpec& s) {
    return std::get<AgglomerateSpec>(s.kind);
}

} // namespace

TEST(Validation, EveryBadInputNamesEntryAndKey) {
    auto const lat = lattice(LatticeKind::SimpleCubic, 1.0, 0.4, kDomain);
    auto const lst = sphereList({Vec3(5, 5, 5), Vec3(2, 2, 2)}, {1.0, 0.5});
    auto const agg = agglomerate(Vec3(5, 5, 5), 3.0, 0.2, 0.4, 10, 1);
    particles::FileSpec fs;
    fs.path = "x.csv";
    ParticleSpec const file = withType(fs, 0);
    std::vector<Case> const cases{
        {"spacing", [](auto& s) { asLattice(s).spacing = 0; }, lat,
         "particles[1].spacing: must be positive, got 0"},
        {"radius", [](auto& s) { asLattice(s).radius = -0.5; }, lat,
         "particles[1].radius: must be positive, got -0.5"},
        {"density", [](auto& s) { asLattice(s).density = kNan; }, lat,
         "particles[1].density: must be positive, got nan"},
        {"region order", [](auto& s) { asLattice(s).region.max.y() = 0; }, lat,
         "particles[1].region: min must be below max"},
        {"region inside", [](auto& s) { asLattice(s).region.max.z() = 11; }, lat,
         "particles[1].region: must lie inside the domain"},
        {"region finite", [](auto& s) { asLattice(s).region.min.x() = kNan; }, lat,
         "particles[1].region.min: must be finite"},
        {"velocity random",
         [](auto& s) {
             asLattice(s).velocity = particles::RandomVelocity{1, 0, 3};
         },
         lat, "particles[1].velocity.random: expected [lo, hi] with lo <= hi"},
        {"velocity fixed", [](auto& s) { asLattice(s).velocity = Vec3(0, kNan, 0); }, lat,
         "particles[1].velocity: must be finite"},
        {"too big for period",
         [](auto& s) { asLattice(s).radius = 5.0; },
         lat,
         "particles[1].radius: a grain of radius 5 does not fit the periodic domain",
         {false, true, false}},
        {"lattice too fine", [](auto& s) { asLattice(s).spacing = 1e-5; }, lat,
         "particles[1].spacing: the lattice would have more than 2^40 sites"},
        {"list radius count",
         [](auto& s) {
             asList(s).radius = {1, 2, 3};
         },
         lst, "particles[1].radius: expected 1 value or one per position (2), got 3"},
        {"list radius value", [](auto& s) { asList(s).radius[1] = 0; }, lst,
         "particles[1].radius[1]: must be positive, got 0"},
        {"list velocity count",
         [](auto& s) {
             asList(s).velocity = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
         },
         lst, "particles[1].velocity: expected none, 1 or one per position (2), got 3"},
        {"list position outside", [](auto& s) { asList(s).position[1] = Vec3(2, -1, 2); }, lst,
         "particles[1].position[1]: centre [2, -1, 2] lies outside the domain"},
        {"list grain crosses wall", [](auto& s) { asList(s).position[0] = Vec3(5, 5, 9.5); }, lst,
         "particles[1].position[0]: grain (centre [5, 5, 9.5], radius 1) crosses the domain "
         "boundary along the non-periodic axis z"},
        {"list density", [](auto& s) { asList(s).density = 0; }, lst,
         "particles[1].density: must be positive, got 0"},
        {"file path", [](auto& s) { std::get<particles::FileSpec>(s.kind).path.clear(); }, file,
         "particles[1].path: must name a CSV file"},
        {"file density", [](auto& s) { std::get<particles::FileSpec>(s.kind).density = -1.0; },
         file, "particles[1].density: must be positive, got -1"},
        {"agg grain radius order", [](auto& s) { asAgg(s).grainRadiusMin = 0.5; }, agg,
         "particles[1].grain_radius: expected [min, max] with 0 < min <= max, got [0.5, 0.4]"},
        {"agg grain radius zero", [](auto& s) { asAgg(s).grainRadiusMin = 0; }, agg,
         "particles[1].grain_radius: expected [min, max] with 0 < min <= max"},
        {"agg grain larger than sphere", [](auto& s) { asAgg(s).grainRadiusMax = 3.0; }, agg,
         "particles[1].grain_radius: max (3) must be below the agglomerate radius (3)"},
        {"agg count", [](auto& s) { asAgg(s).count = -1; }, agg,
         "particles[1].count: must be >= 0, got -1"},
        {"agg radius", [](auto& s) { asAgg(s).radius = 0; }, agg,
         "particles[1].radius: must be positive, got 0"},
        {"agg center", [](auto& s) { asAgg(s).center = Vec3(5, 11, 5); }, agg,
         "particles[1].center: must lie inside the domain"},
        {"agg sphere crosses wall", [](auto& s) { asAgg(s).center = Vec3(1, 5, 5); }, agg,
         "particles[1].radius: the agglomerate sphere (center [1, 5, 5], radius 3) must lie "
         "inside the domain along the non-periodic axis x"},
        {"agg max attempts", [](auto& s) { asAgg(s).maxAttempts = 0; }, agg,
         "particles[1].max_attempts: must be >= 1, got 0"},
        {"agg density", [](auto& s) { asAgg(s).density = std::numeric_limits<double>::infinity(); },
         agg, "particles[1].density: must be positive, got inf"},
        {"agg velocity", [](auto& s) { asAgg(s).velocity = Vec3(kNan, 0, 0); }, agg,
         "particles[1].velocity: must be finite"},
        {"radius range order",
         [](auto& s) {
             asLattice(s).radiusRange = particles::RadiusRange{0.4, 0.3, 0};
         },
         lat, "particles[1].radius: expected [min, max] with 0 < min <= max, got [0.4, 0.3]"},
        {"list radius range zero",
         [](auto& s) {
             asList(s).radiusRange = particles::RadiusRange{0.0, 0.3, 0};
         },
         lst, "particles[1].radius: expected [min, max] with 0 < min <= max, got [0, 0.3]"},
        {"angular velocity", [](auto& s) { s.angularVelocity = Vec3(0, kNan, 0); }, agg,
         "particles[1].angular_velocity: must be finite"},
        {"fixed and moving", [](auto& s) { s.fixed = true; }, agg,
         "particles[1].fixed: a fixed grain is held in place"},
        {"fixed and spinning",
         [](auto& s) {
             s.fixed = true;
             s.angularVelocity = Vec3(0, 0, 1);
         },
         lat, "particles[1].fixed: a fixed grain is held in place"},
    };
    for (auto const& c : cases) {
        ParticleSpec bad = c.base;
        c.mutate(bad);
        // Entry 0 is valid; the bad one is entry 1.
        std::vector<ParticleSpec> const specs{sphereList({Vec3(9, 9, 9)}, {0.5}), bad};
        std::string const msg =
            inputErrorOf([&] { (void)particles::generateGrains(specs, kDomain, c.periodic); });
        EXPECT_NE(msg.find(c.expected), std::string::npos)
            << c.name << ": expected '" << c.expected << "' in '" << msg << "'";
        // The unmutated entry is accepted (files are not read here, only validated).
        if (!std::holds_alternative<particles::FileSpec>(c.base.kind)) {
            std::vector<ParticleSpec> const good{sphereList({Vec3(9, 9, 9)}, {0.5}), c.base};
            EXPECT_NO_THROW((void)particles::generateGrains(good, kDomain, c.periodic)) << c.name;
        }
    }
}

TEST(Validation, BadDomainIsReported) {
    std::vector<ParticleSpec> const specs{sphereList({Vec3(1, 1, 1)}, {0.5})};
    auto const msg = inputErrorOf([&] {
        (void)particles::generateGrains(specs, box(Vec3(0, 0, 0), Vec3(1, 0, 1)),
                                        {false, false, false});
    });
    EXPECT_NE(msg.find("domain: expected finite min < max"), std::string::npos) << msg;
}

TEST(Validation, EmptySceneAndEmptyBoxes) {
    std::vector<ParticleSpec> const none;
    auto const out = particles::generateGrains(none, kDomain, {true, true, true});
    EXPECT_TRUE(out.grains.empty());
    EXPECT_EQ(out.entryUidBegin, (std::vector<std::uint64_t>{0}));
    std::vector<ParticleSpec> const specs{lattice(LatticeKind::SimpleCubic, 1.0, 0.4, kDomain)};
    std::vector<core::AABB> const noBoxes;
    auto const nothing = particles::generateGrains(specs, kDomain, {true, true, true}, noBoxes);
    EXPECT_TRUE(nothing.grains.empty());
    EXPECT_EQ(nothing.entryUidBegin, (std::vector<std::uint64_t>{0, 1000}));
}
