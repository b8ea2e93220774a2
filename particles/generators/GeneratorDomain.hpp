#pragma once
/// The simulation domain as the generators see it: a box and which axes are periodic.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"

#include <array>

namespace regolith::particles {

struct GeneratorDomain {
    core::AABB box;
    std::array<bool, 3> periodic{false, false, false};

    /// Length of the domain along `axis` (the period on a periodic axis).
    [[nodiscard]] double period(int axis) const { return box.max[axis] - box.min[axis]; }
    /// `p` with every periodic coordinate wrapped into [min, max); other coordinates kept.
    /// Pre: p finite.
    [[nodiscard]] core::Vec3 wrap(core::Vec3 const& p) const;
};

/// Do the spheres (a, ra) and (b, rb) overlap, i.e. is |a - b| < ra + rb? Touching spheres
/// do not overlap. Every overlap test of the generators goes through this one expression.
[[nodiscard]] inline bool spheresOverlap(core::Vec3 const& a, double ra, core::Vec3 const& b,
                                         double rb) {
    double const reach = ra + rb;
    return (a - b).squaredNorm() < reach * reach;
}

} // namespace regolith::particles
