#pragma once
/// A union of closed boxes inside the domain, built from boxes grown by a margin with their
/// periodic images folded back into the domain: "every point within `margin` of these boxes".
/// The generators use it for the region in which an entry's grains must be known.
#include "core/math/AABB.hpp"
#include "particles/generators/GeneratorDomain.hpp"

#include <span>
#include <vector>

namespace regolith::particles {

class RegionSet {
public:
    RegionSet() = default;

    /// Adds `box` grown by `margin` (>= 0) on every side, clipped to the domain (closed). On a
    /// periodic axis the parts that stick out of the domain are added shifted by one period
    /// (a grown extent of a period or more covers the whole axis). Pre: box and margin finite.
    void add(core::AABB const& box, double margin, GeneratorDomain const& domain);

    /// Is `p` in one of the boxes (closed)? p is in domain coordinates (wrapped).
    [[nodiscard]] bool containsClosed(core::Vec3 const& p) const;

    /// The boxes, each inside the domain; they may overlap.
    [[nodiscard]] std::span<core::AABB const> boxes() const { return m_boxes; }
    [[nodiscard]] bool empty() const { return m_boxes.empty(); }

private:
    std::vector<core::AABB> m_boxes;
    core::AABB m_bounds; ///< bounding box of m_boxes (valid when not empty)
};

} // namespace regolith::particles
