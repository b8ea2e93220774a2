// [[particles]] entries: the four kinds of particle source (DESIGN.md, "Scene file").
#include "apps/regolith/SceneSections.hpp"
#include "core/config/ValueChecks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

namespace regolith::apps {

using core::isFiniteVec3;
using core::isPositiveFinite;

namespace {

using namespace std::string_view_literals;

constexpr std::array kKindNames{"lattice"sv, "list"sv, "agglomerate"sv, "file"sv};
constexpr std::array kLatticeNames{"sc"sv, "bcc"sv, "fcc"sv, "hcp"sv};
constexpr char const* kPositive = "a positive finite number";

VelocitySpec parseVelocity(core::ConfigTable const& t) {
    VelocitySpec v;
    switch (t.kindOf("velocity")) {
    case core::ConfigKind::Missing:
        return v;
    case core::ConfigKind::Table:
        break;
    default:
        v.mean = t.getIf<core::Vec3>("velocity", isFiniteVec3,
                                     "an array of 3 finite numbers or a table { mean, random, "
                                     "seed }");
        return v;
    }
    auto const table = t.table("velocity");
    v.mean =
        table.getOrIf<core::Vec3>("mean", v.mean, isFiniteVec3, "an array of 3 finite numbers");
    auto const range = table.getOrIf<std::array<double, 2>>(
        "random", {0.0, 0.0},
        [](auto const& r) { return std::isfinite(r[0]) && std::isfinite(r[1]) && r[0] <= r[1]; },
        "an array [min, max] of finite numbers with min <= max");
    v.randomMin = range[0];
    v.randomMax = range[1];
    v.seed = static_cast<std::uint64_t>(
        table.getOrIf<std::int64_t>("seed", 0, core::isNonNegative, "a non-negative integer"));
    return v;
}

LatticeSource parseLattice(core::ConfigTable const& t, core::AABB const& domain) {
    LatticeSource s;
    s.lattice = static_cast<LatticeKind>(t.getChoice("lattice", kLatticeNames));
    s.spacing = t.getIf<double>("spacing", isPositiveFinite, kPositive);
    s.radius = t.getIf<double>("radius", isPositiveFinite, kPositive);
    if (2.0 * s.radius > s.spacing)
        t.fail("radius", fmt::format("grains of radius {} overlap on a lattice with spacing {} "
                                     "(need 2 * radius <= spacing)",
                                     s.radius, s.spacing));
    s.density = t.getIf<double>("density", isPositiveFinite, kPositive);
    s.region = domain;
    if (auto const region = t.findTable("region")) {
        s.region.min =
            region->getIf<core::Vec3>("min", isFiniteVec3, "an array of 3 finite numbers");
        s.region.max =
            region->getIf<core::Vec3>("max", isFiniteVec3, "an array of 3 finite numbers");
        if (!(s.region.max.array() > s.region.min.array()).all())
            region->failExpected("max", "a corner above region.min on every axis");
    }
    s.velocity = parseVelocity(t);
    return s;
}

ListSource parseList(core::ConfigTable const& t) {
    ListSource s;
    s.position = t.getIf<std::vector<core::Vec3>>(
        "position",
        [](auto const& ps) {
            return !ps.empty() && std::all_of(ps.begin(), ps.end(), isFiniteVec3);
        },
        "a non-empty array of [x, y, z] positions");
    std::size_t const n = s.position.size();
    auto const allPositive = [](std::vector<double> const& rs) {
        return std::all_of(rs.begin(), rs.end(), isPositiveFinite);
    };
    if (t.kindOf("radius") == core::ConfigKind::Array)
        s.radius = t.getIf<std::vector<double>>(
            "radius", [&](auto const& rs) { return rs.size() == n && allPositive(rs); },
            fmt::format("one positive finite radius per position ({})", n));
    else
        s.radius.assign(n, t.getIf<double>("radius", isPositiveFinite,
                                           "a positive finite number or an array of them"));
    if (t.has("velocity"))
        s.velocity = t.getIf<std::vector<core::Vec3>>(
            "velocity",
            [&](auto const& vs) {
                return vs.size() == n && std::all_of(vs.begin(), vs.end(), isFiniteVec3);
            },
            fmt::format("one finite [vx, vy, vz] per position ({})", n));
    else
        s.velocity.assign(n, core::Vec3::Zero());
    s.density = t.getIf<double>("density", isPositiveFinite, kPositive);
    return s;
}

AgglomerateSource parseAgglomerate(core::ConfigTable const& t) {
    AgglomerateSource s;
    s.center = t.getIf<core::Vec3>("center", isFiniteVec3, "an array of 3 finite numbers");
    s.radius = t.getIf<double>("radius", isPositiveFinite, kPositive);
    if (t.kindOf("grain_radius") == core::ConfigKind::Array) {
        auto const r = t.getIf<std::array<double, 2>>(
            "grain_radius",
            [](auto const& g) {
                return isPositiveFinite(g[0]) && std::isfinite(g[1]) && g[0] <= g[1];
            },
            "an array [min, max] of positive finite numbers with min <= max, or one number");
        s.grainRadiusMin = r[0];
        s.grainRadiusMax = r[1];
    } else {
        s.grainRadiusMin = s.grainRadiusMax =
            t.getIf<double>("grain_radius", isPositiveFinite, kPositive);
    }
    if (s.grainRadiusMax >= s.radius)
        t.fail("grain_radius", fmt::format("the largest grain ({}) must be smaller than the "
                                           "agglomerate radius ({})",
                                           s.grainRadiusMax, s.radius));
    s.count = t.getIf<std::int64_t>(
        "count", [](std::int64_t c) { return c > 0; }, "a positive integer");
    s.velocity = parseVelocity(t);
    s.density = t.getIf<double>("density", isPositiveFinite, kPositive);
    s.seed = static_cast<std::uint64_t>(
        t.getOrIf<std::int64_t>("seed", 0, core::isNonNegative, "a non-negative integer"));
    return s;
}

FileSource parseFile(core::ConfigTable const& t, std::string const& sceneDir) {
    FileSource s;
    s.path = t.getIf<std::string>(
        "path", [](std::string const& p) { return !p.empty(); }, "a non-empty file name");
    std::filesystem::path const p(s.path);
    s.resolvedPath = p.is_absolute() || sceneDir.empty()
                         ? s.path
                         : (std::filesystem::path(sceneDir) / p).lexically_normal().string();
    return s;
}

} // namespace

ParticleSource parseParticleSource(core::ConfigTable const& entry, core::AABB const& domain,
                                   std::string const& sceneDir) {
    switch (entry.getChoice("kind", kKindNames)) {
    case 0:
        return parseLattice(entry, domain);
    case 1:
        return parseList(entry);
    case 2:
        return parseAgglomerate(entry);
    default:
        return parseFile(entry, sceneDir);
    }
}

std::string_view toString(LatticeKind k) {
    return kLatticeNames[static_cast<std::size_t>(k)];
}

} // namespace regolith::apps
