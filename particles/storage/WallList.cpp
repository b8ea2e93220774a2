#include "particles/storage/WallList.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace regolith::particles {

namespace {

std::string text(core::Vec3 const& v) {
    return fmt::format("({}, {}, {})", v.x(), v.y(), v.z());
}

/// `v` normalised; InputError naming wall `index` and `what` if v is zero or not finite.
core::Vec3 unit(core::Vec3 const& v, std::size_t index, char const* what) {
    double const len = v.norm();
    if (!(len > 0.0) || !std::isfinite(len))
        throw core::InputError(
            fmt::format("wall {}: {} {} must be finite and non-zero", index, what, text(v)));
    return v / len;
}

void requireFinite(core::Vec3 const& v, std::size_t index, char const* what) {
    if (!v.allFinite())
        throw core::InputError(fmt::format("wall {}: {} {} must be finite", index, what, text(v)));
}

void requirePositive(double x, std::size_t index, char const* what) {
    if (!(x > 0.0) || !std::isfinite(x))
        throw core::InputError(
            fmt::format("wall {}: {} = {} must be positive and finite", index, what, x));
}

} // namespace

std::size_t WallList::add(Wall wall) {
    std::size_t const k = m_walls.size();
    WallGeometry& g = wall.geometry;
    requireFinite(g.point, k, "point");
    g.normal = unit(g.normal, k, g.shape == WallShape::Cylinder ? "axis" : "normal");
    if (g.shape == WallShape::Rectangle) {
        g.edge = unit(g.edge - g.edge.dot(g.normal) * g.normal, k,
                      "edge (its part perpendicular to the normal)");
        requirePositive(g.halfSize[0], k, "half of size[0]");
        requirePositive(g.halfSize[1], k, "half of size[1]");
    }
    if (g.shape == WallShape::Disc || g.shape == WallShape::Cylinder) {
        requirePositive(g.radius, k, "radius");
        g.edge = WallGeometry::anyPerpendicular(g.normal); // where the output's seam starts
    }
    WallMotion const& m = wall.motion;
    requireFinite(m.velocity, k, "velocity");
    requireFinite(m.angularVelocity, k, "angular_velocity");
    requireFinite(m.centre, k, "axis_point");
    requireFinite(m.amplitude, k, "amplitude");
    if (!std::isfinite(m.frequency))
        throw core::InputError(fmt::format("wall {}: frequency must be finite", k));
    wall.uid = wallUid(k);
    wall.centre = m.centre;
    wall.velocity = m.velocityAt(0.0);
    wall.moving = m.moves();
    m_moving = m_moving || wall.moving;
    m_start.push_back(g);
    m_walls.push_back(wall);
    m_load.emplace_back();
    m_powerBefore.push_back(0.0);
    m_work.push_back(0.0);
    return k;
}

std::size_t WallList::add(core::Vec3 const& point, core::Vec3 const& normal, std::uint32_t type) {
    Wall w;
    w.geometry.point = point;
    w.geometry.normal = normal;
    w.motion.centre = point;
    w.type = type;
    return add(w);
}

void WallList::moveTo(double t) {
    if (!m_moving)
        return;
    for (std::size_t k = 0; k < m_walls.size(); ++k) {
        Wall& w = m_walls[k];
        if (!w.moving)
            continue;
        core::Vec3 const shift = w.motion.displacement(t);
        w.geometry = m_start[k].moved(w.motion.rotation(t), w.motion.centre, shift);
        w.centre = w.motion.centre + shift;
        w.velocity = w.motion.velocityAt(t);
    }
}

void WallList::resetForces() {
    for (WallLoad& l : m_load)
        l = WallLoad{};
}

void WallList::addWork(double dt) {
    for (std::size_t k = 0; k < m_walls.size(); ++k) {
        m_work[k] += 0.5 * dt * (m_powerBefore[k] + m_load[k].power);
        m_powerBefore[k] = m_load[k].power;
    }
}

void WallList::restartWork() {
    for (std::size_t k = 0; k < m_walls.size(); ++k)
        m_powerBefore[k] = m_load[k].power;
}

} // namespace regolith::particles
