#include "particles/storage/WallList.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace regolith::particles {

std::size_t WallList::add(core::Vec3 const& point, core::Vec3 const& normal, std::uint32_t type) {
    double const len = normal.norm();
    if (!(len > 0.0) || !std::isfinite(len) || !point.allFinite())
        throw core::InputError(fmt::format(
            "wall {}: point ({}, {}, {}) and normal ({}, {}, {}) must be finite and the normal "
            "non-zero",
            m_walls.size(), point.x(), point.y(), point.z(), normal.x(), normal.y(), normal.z()));
    std::size_t const k = m_walls.size();
    m_walls.push_back(Wall{point, normal / len, type, wallUid(k)});
    m_force.push_back(core::Vec3::Zero());
    return k;
}

void WallList::resetForces() {
    for (auto& f : m_force)
        f.setZero();
}

} // namespace regolith::particles
