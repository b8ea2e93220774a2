#pragma once
/// Axis-aligned box [min, max) used for domains, blocks and particle bounds.
#include "core/math/Vec3.hpp"

#include <algorithm>

namespace regolith::core {

struct AABB {
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();

    [[nodiscard]] Vec3 extent() const { return max - min; }
    [[nodiscard]] Vec3 center() const { return 0.5 * (min + max); }
    [[nodiscard]] double volume() const { return extent().prod(); }
    [[nodiscard]] double minEdge() const { return extent().minCoeff(); }

    /// Half-open containment, so the blocks of a forest partition space without double
    /// counting a point on a shared face.
    [[nodiscard]] bool contains(Vec3 const& p) const {
        return (p.array() >= min.array()).all() && (p.array() < max.array()).all();
    }
    /// Closed overlap test: boxes that share a face, edge or corner intersect.
    [[nodiscard]] bool intersectsClosed(AABB const& o) const {
        return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
    }
    /// Overlap with positive volume.
    [[nodiscard]] bool intersectsOpen(AABB const& o) const {
        return (min.array() < o.max.array()).all() && (o.min.array() < max.array()).all();
    }
    /// Squared distance from p to the closest point of the box (0 inside).
    [[nodiscard]] double sqDistance(Vec3 const& p) const {
        Vec3 const d = (min - p).cwiseMax(Vec3::Zero()).cwiseMax(p - max);
        return d.squaredNorm();
    }
    /// Does the closed ball (center, radius) reach into the box?
    [[nodiscard]] bool intersectsSphere(Vec3 const& center, double radius) const {
        return sqDistance(center) < radius * radius;
    }
    [[nodiscard]] AABB shifted(Vec3 const& s) const { return {min + s, max + s}; }
    [[nodiscard]] AABB extended(double margin) const {
        return {min.array() - margin, max.array() + margin};
    }
};

} // namespace regolith::core
