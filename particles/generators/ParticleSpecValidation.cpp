#include "particles/generators/ParticleSpecValidation.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::particles {

namespace {

constexpr std::array<char, 3> kAxisName{'x', 'y', 'z'};

std::string vec(core::Vec3 const& v) {
    return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z());
}

[[noreturn]] void fail(std::string const& key, std::string const& what) {
    throw core::InputError(key + ": " + what);
}

void requirePositive(double v, std::string const& key) {
    if (!std::isfinite(v) || v <= 0.0)
        fail(key, fmt::format("must be positive, got {}", v));
}

void requireFinite(core::Vec3 const& v, std::string const& key) {
    if (!v.allFinite())
        fail(key, fmt::format("must be finite, got {}", vec(v)));
}

/// On periodic axes a grain must not reach its own image.
void requireBelowPeriod(double radius, GeneratorDomain const& domain, std::string const& key) {
    for (int a = 0; a < 3; ++a)
        if (domain.periodic[static_cast<std::size_t>(a)] && 2.0 * radius >= domain.period(a))
            fail(key,
                 fmt::format("a grain of radius {} does not fit the periodic domain (its "
                             "diameter must be below the period {} along {})",
                             radius, domain.period(a), kAxisName[static_cast<std::size_t>(a)]));
}

void validateVelocity(VelocitySpec const& velocity, std::string const& key) {
    if (auto const* fixed = std::get_if<core::Vec3>(&velocity)) {
        requireFinite(*fixed, key);
        return;
    }
    auto const& r = std::get<RandomVelocity>(velocity);
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || r.lo > r.hi)
        fail(key + ".random",
             fmt::format("expected [lo, hi] with lo <= hi, both finite, got [{}, {}]", r.lo, r.hi));
}

void validateRadiusRange(std::optional<RadiusRange> const& r, std::string const& key) {
    if (r && !(std::isfinite(r->min) && std::isfinite(r->max) && r->min > 0.0 && r->min <= r->max))
        fail(key,
             fmt::format("expected [min, max] with 0 < min <= max, got [{}, {}]", r->min, r->max));
}

/// Whether the entry gives its grains a velocity or spin other than 0 (files: see
/// EntrySource, which reads them).
bool givesMotion(ParticleSpec const& s) {
    auto const moving = [](core::Vec3 const& v) { return v != core::Vec3::Zero(); };
    if (s.angularVelocity && moving(*s.angularVelocity))
        return true;
    if (auto const* lattice = std::get_if<LatticeSpec>(&s.kind)) {
        if (auto const* fixed = std::get_if<core::Vec3>(&lattice->velocity))
            return moving(*fixed);
        auto const& r = std::get<RandomVelocity>(lattice->velocity);
        return r.lo != 0.0 || r.hi != 0.0;
    }
    if (auto const* list = std::get_if<ListSpec>(&s.kind))
        return std::any_of(list->velocity.begin(), list->velocity.end(), moving);
    if (auto const* agglomerate = std::get_if<AgglomerateSpec>(&s.kind))
        return moving(agglomerate->velocity);
    return false;
}

/// The keys every kind has: angular_velocity finite, a fixed entry at rest.
void validateEntryKeys(ParticleSpec const& s, std::string const& key) {
    if (s.angularVelocity)
        requireFinite(*s.angularVelocity, key + ".angular_velocity");
    if (s.fixed && givesMotion(s))
        fail(key + ".fixed", "a fixed grain is held in place: its entry may give it no velocity "
                             "or angular_velocity other than 0");
}

void validateLattice(LatticeSpec const& s, std::string const& key, GeneratorDomain const& d) {
    validateRadiusRange(s.radiusRange, key + ".radius");
    requirePositive(s.spacing, key + ".spacing");
    requirePositive(s.radius, key + ".radius");
    requirePositive(s.density, key + ".density");
    requireBelowPeriod(s.radius, d, key + ".radius");
    requireFinite(s.region.min, key + ".region.min");
    requireFinite(s.region.max, key + ".region.max");
    if (!(s.region.min.array() < s.region.max.array()).all())
        fail(key + ".region", fmt::format("min must be below max on every axis, got min = {}, "
                                          "max = {}",
                                          vec(s.region.min), vec(s.region.max)));
    if (!(s.region.min.array() >= d.box.min.array()).all() ||
        !(s.region.max.array() <= d.box.max.array()).all())
        fail(key + ".region",
             fmt::format("must lie inside the domain (min = {}, max = {}), got min = {}, max = {}",
                         vec(d.box.min), vec(d.box.max), vec(s.region.min), vec(s.region.max)));
    // On a non-periodic axis a site is used only if the whole grain lies in the region
    // (LatticeSites::used): a thinner region generates nothing, which is never what was meant.
    for (int a = 0; a < 3; ++a)
        if (!d.periodic[static_cast<std::size_t>(a)] &&
            s.region.max[a] - s.region.min[a] < 2.0 * s.radius)
            fail(key + ".region",
                 fmt::format("[{}, {}] along the non-periodic axis {} is thinner than a grain's "
                             "diameter {}: the lattice would place no grain (a scenario's region "
                             "is its domain: widen the domain there)",
                             s.region.min[a], s.region.max[a],
                             kAxisName[static_cast<std::size_t>(a)], 2.0 * s.radius));
    validateVelocity(s.velocity, key + ".velocity");
}

void validateList(ListSpec const& s, std::string const& key, GeneratorDomain const& d) {
    std::size_t const n = s.position.size();
    validateRadiusRange(s.radiusRange, key + ".radius");
    requirePositive(s.density, key + ".density");
    if (n > 0 && s.radius.size() != 1 && s.radius.size() != n)
        fail(key + ".radius",
             fmt::format("expected 1 value or one per position ({}), got {}", n, s.radius.size()));
    if (n == 0 && s.radius.size() > 1)
        fail(key + ".radius",
             fmt::format("expected at most 1 value when no position is given, got {}",
                         s.radius.size()));
    if (!s.velocity.empty() && s.velocity.size() != 1 && s.velocity.size() != n)
        fail(key + ".velocity", fmt::format("expected none, 1 or one per position ({}), got {}", n,
                                            s.velocity.size()));
    for (std::size_t i = 0; i < s.radius.size(); ++i)
        requirePositive(s.radius[i], fmt::format("{}.radius[{}]", key, i));
    for (std::size_t i = 0; i < s.velocity.size(); ++i)
        requireFinite(s.velocity[i], fmt::format("{}.velocity[{}]", key, i));
    for (std::size_t i = 0; i < n; ++i) {
        double const r = s.radius.size() == 1 ? s.radius[0] : s.radius[i];
        checkGrainPlacement(s.position[i], r, d, fmt::format("{}.position[{}]", key, i));
    }
}

void validateFile(FileSpec const& s, std::string const& key) {
    if (s.path.empty())
        fail(key + ".path", "must name a CSV file, got an empty string");
    if (s.density)
        requirePositive(*s.density, key + ".density");
}

void validateAgglomerate(AgglomerateSpec const& s, std::string const& key,
                         GeneratorDomain const& d) {
    requireFinite(s.center, key + ".center");
    requirePositive(s.radius, key + ".radius");
    requirePositive(s.density, key + ".density");
    requireFinite(s.velocity, key + ".velocity");
    if (!std::isfinite(s.grainRadiusMin) || !std::isfinite(s.grainRadiusMax) ||
        s.grainRadiusMin <= 0.0 || s.grainRadiusMin > s.grainRadiusMax)
        fail(key + ".grain_radius", fmt::format("expected [min, max] with 0 < min <= max, got "
                                                "[{}, {}]",
                                                s.grainRadiusMin, s.grainRadiusMax));
    if (s.grainRadiusMax >= s.radius)
        fail(key + ".grain_radius",
             fmt::format("max ({}) must be below the agglomerate radius ({})", s.grainRadiusMax,
                         s.radius));
    if (s.count < 0)
        fail(key + ".count", fmt::format("must be >= 0, got {}", s.count));
    if (s.maxAttempts < 1)
        fail(key + ".max_attempts", fmt::format("must be >= 1, got {}", s.maxAttempts));
    requireBelowPeriod(s.grainRadiusMax, d, key + ".grain_radius");
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        double const c = s.center[a];
        if (c < d.box.min[a] || c >= d.box.max[a])
            fail(key + ".center", fmt::format("must lie inside the domain (min = {}, max = {}), "
                                              "got {}",
                                              vec(d.box.min), vec(d.box.max), vec(s.center)));
        if (!d.periodic[ua] && (c - s.radius < d.box.min[a] || c + s.radius > d.box.max[a]))
            fail(key + ".radius",
                 fmt::format("the agglomerate sphere (center {}, radius {}) must lie inside the "
                             "domain along the non-periodic axis {} ([{}, {}])",
                             vec(s.center), s.radius, kAxisName[ua], d.box.min[a], d.box.max[a]));
    }
}

} // namespace

std::string entryKey(std::size_t index) {
    return fmt::format("particles[{}]", index);
}

void checkGrainPlacement(core::Vec3 const& centre, double radius, GeneratorDomain const& d,
                         std::string const& what) {
    if (!std::isfinite(radius) || radius <= 0.0)
        fail(what, fmt::format("radius must be positive, got {}", radius));
    requireFinite(centre, what);
    requireBelowPeriod(radius, d, what);
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        double const c = centre[a];
        if (c < d.box.min[a] || c >= d.box.max[a])
            fail(what, fmt::format("centre {} lies outside the domain (min = {}, max = {})",
                                   vec(centre), vec(d.box.min), vec(d.box.max)));
        if (!d.periodic[ua] && (c - radius < d.box.min[a] || c + radius > d.box.max[a]))
            fail(what, fmt::format("grain (centre {}, radius {}) crosses the domain boundary "
                                   "along the non-periodic axis {} ([{}, {}])",
                                   vec(centre), radius, kAxisName[ua], d.box.min[a], d.box.max[a]));
    }
}

void validateParticleSpecs(std::span<ParticleSpec const> specs, GeneratorDomain const& domain) {
    if (!domain.box.min.allFinite() || !domain.box.max.allFinite() ||
        !(domain.box.min.array() < domain.box.max.array()).all())
        fail("domain", fmt::format("expected finite min < max on every axis, got min = {}, "
                                   "max = {}",
                                   vec(domain.box.min), vec(domain.box.max)));
    for (std::size_t i = 0; i < specs.size(); ++i) {
        std::string const key = entryKey(i);
        auto const& kind = specs[i].kind;
        if (auto const* lattice = std::get_if<LatticeSpec>(&kind))
            validateLattice(*lattice, key, domain);
        else if (auto const* list = std::get_if<ListSpec>(&kind))
            validateList(*list, key, domain);
        else if (auto const* file = std::get_if<FileSpec>(&kind))
            validateFile(*file, key);
        else
            validateAgglomerate(std::get<AgglomerateSpec>(kind), key, domain);
        validateEntryKeys(specs[i], key);
    }
}

} // namespace regolith::particles
