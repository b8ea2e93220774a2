// [[particles]] entries: the four kinds of particle source (docs/design.md, "Scene file"), read
// into the generators' input types. Only what TOML decides is checked here (key names, types,
// choices, integer ranges that the target types cannot hold); the value rules live in one
// place, particles::validateParticleSpecs, which parseScene runs on the result.
#include "apps/regolith/SceneSections.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string_view>
#include <vector>

namespace regolith::apps {

namespace {

using namespace std::string_view_literals;

constexpr std::array kKindNames{"lattice"sv, "list"sv, "agglomerate"sv, "file"sv};
/// In the order of particles::LatticeKind.
constexpr std::array kLatticeNames{"sc"sv, "hcp"sv};

/// seed = n: a non-negative integer (TOML integers are signed 64-bit).
std::uint64_t seedOr(core::ConfigTable const& t, std::string_view key, std::uint64_t fallback) {
    if (!t.has(key))
        return fallback;
    return static_cast<std::uint64_t>(t.getIf<std::int64_t>(
        key, [](std::int64_t s) { return s >= 0; }, "a non-negative integer"));
}

/// velocity = [vx, vy, vz] (every grain) or velocity = { random = [lo, hi], seed = s }.
particles::VelocitySpec parseVelocity(core::ConfigTable const& t) {
    auto const kind = t.kindOf("velocity");
    if (kind == core::ConfigKind::Missing)
        return core::Vec3(0.0, 0.0, 0.0);
    if (kind == core::ConfigKind::Table) {
        auto const table = t.table("velocity");
        auto const range = table.get<std::array<double, 2>>("random");
        return particles::RandomVelocity{range[0], range[1], seedOr(table, "seed", 0)};
    }
    if (kind != core::ConfigKind::Array)
        t.failExpected("velocity", "[vx, vy, vz] or a table { random = [lo, hi], seed = n }");
    return t.get<core::Vec3>("velocity");
}

/// radius = { uniform = [min, max], seed = s }: a range drawn per grain.
particles::RadiusRange parseRadiusRange(core::ConfigTable const& t) {
    auto const table = t.table("radius");
    auto const range = table.get<std::array<double, 2>>("uniform");
    return {range[0], range[1], seedOr(table, "seed", 0)};
}

particles::LatticeSpec parseLattice(core::ConfigTable const& t, core::AABB const& domain) {
    particles::LatticeSpec s;
    s.lattice = static_cast<particles::LatticeKind>(t.getChoice("lattice", kLatticeNames));
    s.spacing = t.get<double>("spacing");
    // radius = r, [min, max] or { uniform = [min, max], seed = s }; `radius` is the largest.
    if (t.kindOf("radius") == core::ConfigKind::Table) {
        s.radiusRange = parseRadiusRange(t);
    } else if (t.kindOf("radius") == core::ConfigKind::Array) {
        auto const range = t.get<std::array<double, 2>>("radius");
        s.radiusRange = particles::RadiusRange{range[0], range[1], 0};
    } else {
        s.radius = t.get<double>("radius");
    }
    if (s.radiusRange)
        s.radius = s.radiusRange->max;
    s.density = t.get<double>("density");
    s.region = domain;
    if (auto const region = t.findTable("region")) {
        s.region.min = region->get<core::Vec3>("min");
        s.region.max = region->get<core::Vec3>("max");
    }
    s.velocity = parseVelocity(t);
    return s;
}

/// List velocities: [vx, vy, vz] for every grain, or [[vx, vy, vz], ...] (one, or one per
/// position), or none (at rest). The forms differ in the type of the first element.
std::vector<core::Vec3> parseListVelocity(core::ConfigTable const& t) {
    if (!t.has("velocity") || t.describe("velocity") == "[]")
        return {};
    if (t.describe("velocity").starts_with("[["))
        return t.get<std::vector<core::Vec3>>("velocity");
    if (t.kindOf("velocity") != core::ConfigKind::Array)
        t.failExpected("velocity", "[vx, vy, vz] or an array of them, one per position");
    return {t.get<core::Vec3>("velocity")};
}

particles::ListSpec parseList(core::ConfigTable const& t) {
    particles::ListSpec s;
    s.position = t.get<std::vector<core::Vec3>>("position");
    if (t.kindOf("radius") == core::ConfigKind::Table) {
        s.radiusRange = parseRadiusRange(t);
        s.radius = {s.radiusRange->max};
    } else if (t.kindOf("radius") == core::ConfigKind::Array) {
        s.radius = t.get<std::vector<double>>("radius");
    } else {
        s.radius = {t.get<double>("radius")};
    }
    s.velocity = parseListVelocity(t);
    s.density = t.get<double>("density");
    return s;
}

particles::AgglomerateSpec parseAgglomerate(core::ConfigTable const& t) {
    particles::AgglomerateSpec s;
    s.center = t.get<core::Vec3>("center");
    s.radius = t.get<double>("radius");
    if (t.kindOf("grain_radius") == core::ConfigKind::Array) {
        auto const r = t.get<std::array<double, 2>>("grain_radius");
        s.grainRadiusMin = r[0];
        s.grainRadiusMax = r[1];
    } else {
        s.grainRadiusMin = s.grainRadiusMax = t.get<double>("grain_radius");
    }
    s.count = t.get<std::int64_t>("count");
    s.velocity = t.getOr<core::Vec3>("velocity", core::Vec3::Zero());
    s.density = t.get<double>("density");
    s.seed = seedOr(t, "seed", s.seed);
    s.maxAttempts = t.getOr<std::int64_t>("max_attempts", s.maxAttempts);
    return s;
}

particles::FileSpec parseFile(core::ConfigTable const& t, std::string const& sceneDir) {
    particles::FileSpec s;
    s.path = t.get<std::string>("path");
    // Relative to the scene file; an empty path stays empty for the validation to reject.
    std::filesystem::path const p(s.path);
    if (!s.path.empty() && !p.is_absolute() && !sceneDir.empty()) {
        s.path = (std::filesystem::path(sceneDir) / p).lexically_normal().string();
        s.resolvedFrom = sceneDir;
    }
    if (t.has("density"))
        s.density = t.get<double>("density");
    return s;
}

} // namespace

particles::ParticleSpec parseParticleSource(core::ConfigTable const& entry,
                                            core::AABB const& domain, std::string const& sceneDir) {
    particles::ParticleSpec spec;
    switch (entry.getChoice("kind", kKindNames)) {
    case 0:
        spec.kind = parseLattice(entry, domain);
        break;
    case 1:
        spec.kind = parseList(entry);
        break;
    case 2:
        spec.kind = parseAgglomerate(entry);
        break;
    default:
        spec.kind = parseFile(entry, sceneDir);
        break;
    }
    spec.type = parseMaterialType(entry);
    if (entry.has("angular_velocity"))
        spec.angularVelocity = entry.get<core::Vec3>("angular_velocity");
    spec.fixed = entry.getOr<bool>("fixed", false);
    return spec;
}

std::uint32_t parseMaterialType(core::ConfigTable const& entry) {
    return static_cast<std::uint32_t>(entry.getOrIf<std::int64_t>(
        "type", 0,
        [](std::int64_t n) {
            return n >= 0 && n <= std::int64_t{std::numeric_limits<std::uint32_t>::max()};
        },
        "a material index (an integer in [0, 4294967295])"));
}

} // namespace regolith::apps
