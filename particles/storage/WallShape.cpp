#include "particles/storage/WallShape.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

WallTouch WallGeometry::touchOtherShape(core::Vec3 const& x) const {
    core::Vec3 const d = x - point;
    double const h = d.dot(normal);
    core::Vec3 const radial = d - h * normal; // x's offset from the axis or in the plate's plane
    if (shape == WallShape::Cylinder) {
        double const rho = radial.norm();
        core::Vec3 const out = rho > 0.0 ? core::Vec3(radial / rho) : anyPerpendicular(normal);
        return inner ? WallTouch{radius - rho, -out} : WallTouch{rho - radius, out};
    }
    // A plate: its point nearest to x, in its plane.
    core::Vec3 nearest = radial;
    if (shape == WallShape::Rectangle) {
        core::Vec3 const side = normal.cross(edge);
        nearest = std::clamp(radial.dot(edge), -halfSize[0], halfSize[0]) * edge +
                  std::clamp(radial.dot(side), -halfSize[1], halfSize[1]) * side;
    } else if (double const rho = radial.norm(); rho > radius) {
        nearest *= radius / rho;
    }
    core::Vec3 const away = d - nearest; // from the plate's nearest point to x
    double const dist = away.norm();
    if (!(dist > 0.0))
        return {0.0, normal};
    return {dist, away / dist};
}

} // namespace regolith::particles
