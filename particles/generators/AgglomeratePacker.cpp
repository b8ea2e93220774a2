#include "particles/generators/AgglomeratePacker.hpp"

#include "core/Error.hpp"
#include "core/memory/MemoryBudget.hpp"
#include "core/random/CounterRng.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

namespace regolith::particles {

namespace {

/// Uniform point in the closed unit ball by rejection from the cube [-1, 1)^3.
core::Vec3 pointInUnitBall(core::random::CounterRng& rng) {
    while (true) {
        // One statement per component: the draw order is part of the contract.
        double const x = rng.uniform(-1.0, 1.0);
        double const y = rng.uniform(-1.0, 1.0);
        double const z = rng.uniform(-1.0, 1.0);
        core::Vec3 const u(x, y, z);
        if (u.squaredNorm() <= 1.0)
            return u;
    }
}

/// Random sequential addition of equal spheres jams at a packing fraction of about 0.38
/// (Torquato, Uche & Stillinger 2006, Phys. Rev. E 74, 061308: 0.3841).
constexpr double kRsaJammingFraction = 0.38;

} // namespace

std::vector<GrainInit> packAgglomerate(ParticleSpec const& entrySpec, std::uint64_t uidOffset,
                                       std::uint32_t entry, GeneratorDomain const& domain,
                                       OverlapIndex const& obstacles, std::string const& key) {
    auto const& spec = std::get<AgglomerateSpec>(entrySpec.kind);
    auto const count = static_cast<std::size_t>(spec.count);
    // The grains' volume is at least count r_min^3: a count that cannot fit is refused before
    // the arrays for it are allocated (10^12 grains would end in std::bad_alloc).
    double const rMin = spec.grainRadiusMin;
    double const leastFraction = static_cast<double>(spec.count) * (rMin / spec.radius) *
                                 (rMin / spec.radius) * (rMin / spec.radius);
    if (leastFraction >= 1.0)
        throw core::InputError(fmt::format(
            "{}: {} grains cannot fit in the sphere: their packing fraction sum(r^3)/radius^3 "
            "is at least {:.4f} with grain_radius {} and radius {}; decrease count or "
            "grain_radius, or increase radius",
            key, spec.count, leastFraction, rMin, spec.radius));
    core::requireMemory(static_cast<double>(spec.count) *
                            static_cast<double>(sizeof(GrainInit) +
                                                sizeof(core::random::CounterRng) +
                                                sizeof(std::size_t)),
                        key + ".count", fmt::format("an agglomerate of {} grains", spec.count));
    std::vector<core::random::CounterRng> rng;
    rng.reserve(count);
    std::vector<GrainInit> grains(count);
    double volumeSum = 0.0; // sum of r^3, in index order so every rank gets the same value
    for (std::size_t i = 0; i < count; ++i) {
        GrainInit& g = grains[i];
        g.uid = uidOffset + i;
        rng.emplace_back(spec.seed, g.uid);
        g.radius = spec.grainRadiusMin < spec.grainRadiusMax
                       ? rng.back().uniform(spec.grainRadiusMin, spec.grainRadiusMax)
                       : spec.grainRadiusMin;
        g.velocity = spec.velocity;
        g.density = spec.density;
        g.mass = sphereMass(g.radius, spec.density);
        g.type = entrySpec.type;
        g.entry = entry;
        g.fixed = entrySpec.fixed;
        if (entrySpec.angularVelocity)
            g.angularVelocity = *entrySpec.angularVelocity;
        volumeSum += g.radius * g.radius * g.radius;
    }
    double const fraction = volumeSum / (spec.radius * spec.radius * spec.radius);
    auto fractionNote = [&] {
        return fmt::format("the requested packing fraction is sum(r^3)/radius^3 = {:.4f} "
                           "(random sequential insertion jams near {} for equal spheres{}); "
                           "increase radius or max_attempts, or decrease count or grain_radius",
                           fraction, kRsaJammingFraction,
                           obstacles.empty() ? ""
                                             : ", and grains of earlier entries count as "
                                               "obstacles");
    };
    if (fraction >= 1.0)
        throw core::InputError(
            fmt::format("{}: {} grains cannot fit in the sphere: {}", key, count, fractionNote()));

    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return grains[a].radius > grains[b].radius;
    });

    OverlapIndex placed(domain);
    for (std::size_t n = 0; n < count; ++n) {
        std::size_t const i = order[n];
        GrainInit& g = grains[i];
        double const freeRadius = spec.radius - g.radius;
        bool done = false;
        for (std::int64_t attempt = 0; attempt < spec.maxAttempts && !done; ++attempt) {
            core::Vec3 const offset = freeRadius * pointInUnitBall(rng[i]);
            core::Vec3 const p = domain.wrap(spec.center + offset);
            if (placed.overlaps(p, g.radius) || obstacles.overlaps(p, g.radius))
                continue;
            g.position = p;
            if (entrySpec.angularVelocity)
                g.velocity += entrySpec.angularVelocity->cross(offset);
            placed.insert(p, g.radius);
            done = true;
        }
        if (!done)
            throw core::InputError(fmt::format(
                "{}: could not place grain {} of {} (radius {}) without overlap in {} attempts "
                "({} grains placed); {}",
                key, n + 1, count, g.radius, spec.maxAttempts, n, fractionNote()));
    }
    return grains;
}

} // namespace regolith::particles
