#pragma once
/// The `[[insert]]` entries of a scene: grains poured into a region during the run, as
/// LAMMPS's `fix pour` (docs/guide/walls.md). Plain data; the scene reader fills it.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"

#include <cstdint>
#include <optional>

namespace regolith::particles {

/// Where inserted grains are placed: a box, or a cylinder from `base` along `axis`.
struct InsertRegion {
    enum class Shape : std::uint8_t { Box, Cylinder } shape = Shape::Box;
    core::AABB box;                        ///< box: `min`, `max`
    core::Vec3 base = core::Vec3::Zero();  ///< cylinder: centre of one end
    core::Vec3 axis = core::Vec3::UnitZ(); ///< cylinder: unit, from `base` to the other end
    double radius = 0.0;                   ///< cylinder
    double length = 0.0;                   ///< cylinder, along `axis`

    /// The smallest axis-aligned box holding the region.
    [[nodiscard]] core::AABB bounds() const;
    [[nodiscard]] double volume() const;
};

/// One `[[insert]]` entry. Every grain lies wholly inside the region, overlaps no grain and
/// no wall, and is drawn from core::random::CounterRng(seed, uid, batch): its radius uniform in
/// [radiusMin, radiusMax], then its centre uniform over the positions that keep it inside the
/// region, again until it fits (at most `attempts` times; a grain that does not fit waits
/// for the next batch).
struct InsertSpec {
    InsertRegion region;        ///< `region`
    std::int64_t count = 0;     ///< `count`: grains in all
    std::optional<double> rate; ///< `rate` [grains/time]; none: all at once
    std::int64_t every = 100;   ///< `every`: steps between two batches
    double radiusMin = 0.0;     ///< `radius` = r or [min, max] [length]
    double radiusMax = 0.0;
    double density = 1.0;                     ///< `density` [mass/length^3]
    core::Vec3 velocity = core::Vec3::Zero(); ///< `velocity` [length/time]
    std::uint32_t type = 0;                   ///< `type`: material index
    std::uint64_t seed = 0;                   ///< `seed`
    int attempts = 100;                       ///< `attempts` per grain and batch
};

} // namespace regolith::particles
