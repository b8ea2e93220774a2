#include "apps/regolith/InsertSection.hpp"

#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/config/ValueChecks.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/generators/GrainInsertion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regolith::apps {

namespace {

using core::isPositiveFinite;
using particles::InsertRegion;

constexpr std::string_view kVector = "an array of 3 finite numbers";

InsertRegion parseRegion(core::ConfigTable const& entry) {
    core::ConfigTable const t = entry.table("region");
    InsertRegion r;
    if (t.has("min") || t.has("max")) {
        r.box.min = t.getIf<core::Vec3>("min", core::isFiniteVec3, kVector);
        r.box.max = t.getIf<core::Vec3>(
            "max",
            [&](core::Vec3 const& m) {
                return m.allFinite() && (m.array() > r.box.min.array()).all();
            },
            "3 finite numbers above min");
        for (char const* key : {"base", "axis", "radius", "length"})
            if (t.has(key))
                t.fail(key, "does not apply to a box region (min, max)");
        return r;
    }
    r.shape = InsertRegion::Shape::Cylinder;
    r.base = t.getIf<core::Vec3>("base", core::isFiniteVec3, kVector);
    r.axis = t.getIf<core::Vec3>(
        "axis", [](core::Vec3 const& a) { return a.allFinite() && a.norm() > 0.0; },
        "a non-zero vector of 3 finite numbers");
    r.axis.normalize();
    r.radius = t.getIf<double>("radius", isPositiveFinite, "a positive finite length");
    r.length = t.getIf<double>("length", isPositiveFinite, "a positive finite length");
    return r;
}

} // namespace

particles::InsertSpec parseInsert(core::ConfigTable const& t, domain::ForestSpec const& forest) {
    particles::InsertSpec s;
    if (!t.has("region"))
        t.fail("region", "missing: expected { min = [..], max = [..] } (a box) or { base = [..], "
                         "axis = [..], radius = r, length = l } (a cylinder)");
    s.region = parseRegion(t);
    s.count = t.getIf<std::int64_t>(
        "count", [](std::int64_t n) { return n > 0; }, "a positive integer");
    if (t.has("rate"))
        s.rate = t.getIf<double>("rate", isPositiveFinite,
                                 "a positive finite number of grains per time");
    s.every = t.getOrIf<std::int64_t>(
        "every", s.every, [](std::int64_t n) { return n > 0; }, "a positive number of steps");
    if (t.kindOf("radius") == core::ConfigKind::Array) {
        auto const r = t.getIf<std::array<double, 2>>(
            "radius",
            [](auto const& v) {
                return isPositiveFinite(v[0]) && v[1] >= v[0] && std::isfinite(v[1]);
            },
            "a positive length or [min, max] with 0 < min <= max");
        s.radiusMin = r[0];
        s.radiusMax = r[1];
    } else {
        s.radiusMin = s.radiusMax = t.getIf<double>(
            "radius", isPositiveFinite, "a positive length or [min, max] with 0 < min <= max");
    }
    s.density = t.getIf<double>("density", isPositiveFinite, "a positive finite number");
    s.velocity = t.getOrIf<core::Vec3>("velocity", s.velocity, core::isFiniteVec3, kVector);
    s.type = parseMaterialType(t);
    s.seed = static_cast<std::uint64_t>(t.getOrIf<std::int64_t>(
        "seed", 0, [](std::int64_t v) { return v >= 0; }, "a non-negative integer"));
    s.attempts = t.getOrIf<int>(
        "attempts", s.attempts, [](int n) { return n > 0; }, "a positive integer");

    core::AABB const bounds = s.region.bounds();
    core::AABB const& domain = forest.domain;
    core::ConfigTable const region = t.table("region");
    if (!((bounds.min.array() >= domain.min.array()).all() &&
          (bounds.max.array() <= domain.max.array()).all()))
        region.fail(s.region.shape == InsertRegion::Shape::Box ? "max" : "base",
                    fmt::format("the region reaches from [{}, {}, {}] to [{}, {}, {}], outside the "
                                "domain [{}, {}, {}] to [{}, {}, {}]; expected a region inside it",
                                bounds.min.x(), bounds.min.y(), bounds.min.z(), bounds.max.x(),
                                bounds.max.y(), bounds.max.z(), domain.min.x(), domain.min.y(),
                                domain.min.z(), domain.max.x(), domain.max.y(), domain.max.z()));
    double const narrowest = s.region.shape == InsertRegion::Shape::Box
                                 ? s.region.box.minEdge()
                                 : std::min(2.0 * s.region.radius, s.region.length);
    if (!(2.0 * s.radiusMax < narrowest))
        t.fail("radius", fmt::format("a grain of radius {} does not fit in the region, whose "
                                     "narrowest extent is {}; expected a radius below {}",
                                     s.radiusMax, narrowest, 0.5 * narrowest));
    return s;
}

std::int64_t batchSize(particles::InsertSpec const& spec, double dt) {
    if (!spec.rate)
        return spec.count;
    // Rounded up, but not for the product's rounding above a whole number (5000 x 500 x 2e-5
    // is 50.00000000000001): a relative 1e-12 below it still counts as it.
    double const exact = *spec.rate * static_cast<double>(spec.every) * dt;
    double const perBatch = std::ceil(exact * (1.0 - 1e-12));
    return std::min(spec.count, static_cast<std::int64_t>(std::max(perBatch, 1.0)));
}

void checkBatchDensity(particles::InsertSpec const& spec, std::size_t index, double dt) {
    std::int64_t const batch = batchSize(spec, dt);
    double const grain = 4.0 / 3.0 * std::numbers::pi * std::pow(spec.radiusMin, 3);
    double const fraction = static_cast<double>(batch) * grain / spec.region.volume();
    if (fraction <= particles::kRandomAdditionLimit)
        return;
    throw core::InputError(fmt::format(
        "insert[{}].{}: a batch of {} grains of radius {} or more fills {:.3g} of the region's "
        "volume {:.6g}, more than random placement without overlap reaches ({}: the jamming "
        "limit of random sequential addition); expected at most {} grains per batch (a lower "
        "rate, fewer steps between batches, or a larger region)",
        index, spec.rate ? "rate" : "count", batch, spec.radiusMin, fraction, spec.region.volume(),
        particles::kRandomAdditionLimit,
        static_cast<std::int64_t>(particles::kRandomAdditionLimit * spec.region.volume() / grain)));
}

} // namespace regolith::apps
