#pragma once
/// The surface of a wall at one instant: an infinite plane (a half-space), a finite rectangle
/// or disc (thin plates, touched from either side) or an infinite cylinder (touched from
/// inside or outside). One rule serves every shape: a sphere of radius r centred at x touches
/// the wall where r exceeds the signed distance of x from the surface, along the unit normal
/// from the surface's nearest point towards x.
#include "core/math/Vec3.hpp"

#include <cstdint>

namespace regolith::particles {

enum class WallShape : std::uint8_t { Plane, Rectangle, Disc, Cylinder };

/// Where a sphere centre lies relative to a wall surface.
struct WallTouch {
    /// Signed distance from the surface, positive on the grains' side [length].
    double distance = 0.0;
    /// Unit vector from the surface's nearest point towards the centre.
    core::Vec3 normal = core::Vec3::UnitZ();
};

/// A wall's surface. Directions are unit vectors (WallList::add normalises them).
struct WallGeometry {
    WallShape shape = WallShape::Plane;
    /// Plane: a point on it; rectangle, disc: the centre; cylinder: a point on the axis.
    core::Vec3 point = core::Vec3::Zero();
    /// Plane: the normal out of the solid, into the grains' half-space; rectangle, disc: the
    /// plate's normal; cylinder: the axis direction.
    core::Vec3 normal = core::Vec3::UnitZ();
    /// Rectangle: the direction of the sides of length 2 halfSize[0], perpendicular to normal
    /// (the other sides run along normal x edge); disc, cylinder: a perpendicular that turns
    /// with the wall (where its drawing starts, so that a turning drum is seen to turn).
    core::Vec3 edge = core::Vec3::UnitX();
    double halfSize[2] = {0.0, 0.0}; ///< rectangle: half side lengths [length]
    double radius = 0.0;             ///< disc, cylinder [length]
    bool inner = true;               ///< cylinder: the grains are inside

    /// Where `x` lies relative to the surface (see WallTouch). On a plate's mid-plane or a
    /// cylinder's axis, where the nearest point is not unique, the plate normal or the
    /// direction of the first perpendicular axis is taken. The plane inline (once per grain and
    /// wall and step in the detection), the other shapes out of line.
    [[nodiscard]] WallTouch touch(core::Vec3 const& x) const {
        if (shape == WallShape::Plane)
            return {(x - point).dot(normal), normal};
        return touchOtherShape(x);
    }
    /// touch(x).distance, the same bits; for a plane without the normal (the detection asks
    /// every grain, and only the few that touch for the normal).
    [[nodiscard]] double distance(core::Vec3 const& x) const {
        if (shape == WallShape::Plane)
            return (x - point).dot(normal);
        return touchOtherShape(x).distance;
    }

    /// A unit vector perpendicular to the unit vector `n`: n crossed with the coordinate axis
    /// least aligned with it.
    [[nodiscard]] static core::Vec3 anyPerpendicular(core::Vec3 const& n) {
        Eigen::Index least = 0;
        n.cwiseAbs().minCoeff(&least);
        return n.cross(core::Vec3::Unit(least)).normalized();
    }

    /// This surface rotated by `rotation` about `pivot`, then shifted by `shift`.
    [[nodiscard]] WallGeometry moved(core::Quat const& rotation, core::Vec3 const& pivot,
                                     core::Vec3 const& shift) const {
        WallGeometry g = *this;
        g.point = pivot + rotation * (point - pivot) + shift;
        g.normal = rotation * normal;
        g.edge = rotation * edge;
        return g;
    }

private:
    [[nodiscard]] WallTouch touchOtherShape(core::Vec3 const& x) const;
};

} // namespace regolith::particles
