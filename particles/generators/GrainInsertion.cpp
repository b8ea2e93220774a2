#include "particles/generators/GrainInsertion.hpp"

#include "core/random/CounterRng.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regolith::particles {

core::AABB InsertRegion::bounds() const {
    if (shape == Shape::Box)
        return box;
    // Per axis, the disc of radius R perpendicular to `axis` reaches R sqrt(1 - a_i^2).
    core::Vec3 const reach =
        radius * (core::Vec3::Ones() - axis.cwiseProduct(axis)).cwiseMax(0.0).cwiseSqrt();
    core::Vec3 const top = base + length * axis;
    return {base.cwiseMin(top) - reach, base.cwiseMax(top) + reach};
}

double InsertRegion::volume() const {
    return shape == Shape::Box ? box.volume() : std::numbers::pi * radius * radius * length;
}

Uid insertedUid(std::size_t entry, std::uint64_t n) {
    return makeUid(kFirstReservedRank - 1 - static_cast<int>(entry), n);
}

long insertEntryOf(Uid uid) {
    int const rank = uidRank(uid);
    return rank < kFirstReservedRank ? static_cast<long>(kFirstReservedRank - 1 - rank) : -1;
}

namespace {

/// A centre that keeps a grain of radius r inside the region, from `rng`.
core::Vec3 drawCentre(InsertRegion const& region, double r, core::random::CounterRng& rng) {
    if (region.shape == InsertRegion::Shape::Box) {
        core::Vec3 x;
        for (int a = 0; a < 3; ++a) {
            double const lo = region.box.min[a] + r, hi = region.box.max[a] - r;
            x[a] = lo < hi ? rng.uniform(lo, hi) : 0.5 * (lo + hi);
        }
        return x;
    }
    // Uniform over the disc of radius R - r (sqrt of a uniform radius fraction), and along the
    // axis in [r, length - r].
    double const reach = std::max(region.radius - r, 0.0);
    double const rho = reach * std::sqrt(rng.uniform());
    double const phi = 2.0 * std::numbers::pi * rng.uniform();
    double const t =
        r < region.length - r ? rng.uniform(r, region.length - r) : 0.5 * region.length;
    core::Vec3 const u = WallGeometry::anyPerpendicular(region.axis);
    core::Vec3 const v = region.axis.cross(u);
    return region.base + t * region.axis + rho * (std::cos(phi) * u + std::sin(phi) * v);
}

/// |x - y| below a + b, with the minimum image along the periodic axes.
bool overlap(core::Vec3 const& x, double a, core::Vec3 const& y, double b,
             PeriodicLengths const& periodic) {
    core::Vec3 d = x - y;
    for (int k = 0; k < 3; ++k)
        if (double const len = periodic[static_cast<std::size_t>(k)]; len > 0.0)
            d[k] -= len * std::round(d[k] / len);
    double const reach = a + b;
    return d.squaredNorm() < reach * reach;
}

} // namespace

std::vector<GrainInit> placeBatch(InsertSpec const& spec, std::size_t entry, std::uint64_t batch,
                                  std::uint64_t first, std::int64_t wanted,
                                  std::span<PlacedSphere const> near, WallList const& walls,
                                  PeriodicLengths const& periodic) {
    std::vector<GrainInit> out;
    auto fits = [&](core::Vec3 const& x, double r) {
        for (Wall const& w : walls)
            if (w.distance(x) < r)
                return false;
        for (PlacedSphere const& s : near)
            if (overlap(x, r, s.centre, s.radius, periodic))
                return false;
        for (GrainInit const& g : out)
            if (overlap(x, r, g.position, g.radius, periodic))
                return false;
        return true;
    };
    for (std::int64_t k = 0; k < wanted; ++k) {
        Uid const uid = insertedUid(entry, first + static_cast<std::uint64_t>(k));
        core::random::CounterRng rng(spec.seed, uid, static_cast<std::uint32_t>(batch));
        bool placed = false;
        for (int attempt = 0; attempt < spec.attempts && !placed; ++attempt) {
            double const r = spec.radiusMin < spec.radiusMax
                                 ? rng.uniform(spec.radiusMin, spec.radiusMax)
                                 : spec.radiusMin;
            core::Vec3 const x = drawCentre(spec.region, r, rng);
            if (!fits(x, r))
                continue;
            GrainInit g;
            g.uid = uid;
            g.position = x;
            g.velocity = spec.velocity;
            g.radius = r;
            g.density = spec.density;
            g.mass = sphereMass(r, spec.density);
            g.type = spec.type;
            g.entry = static_cast<std::uint32_t>(entry);
            out.push_back(g);
            placed = true;
        }
        if (!placed)
            break;
    }
    return out;
}

} // namespace regolith::particles
