#pragma once
/// Infinite plane walls: half-spaces that are global (known on every rank) and fixed. Few
/// in number, so stored apart from the spheres and tested against every sphere.
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

/// The solid half-space {x : (x - point) . normal < 0}. `normal` is unit length and points
/// out of the solid, into the space where the particles are.
struct Wall {
    core::Vec3 point = core::Vec3::Zero();
    core::Vec3 normal = core::Vec3::UnitZ();
    std::uint32_t type = 0; ///< material index into the contact model's MaterialTable
    Uid uid = kInvalidUid;  ///< `wallUid(index)`: the key of its contacts' history

    /// Signed distance of `x` from the wall surface, positive on the particle side.
    [[nodiscard]] double distance(core::Vec3 const& x) const { return (x - point).dot(normal); }
};

/// The uid of the wall with index `index`: rank field kGlobalObjectRank, so it never collides
/// with a particle uid.
constexpr Uid wallUid(std::size_t index) {
    return makeUid(kGlobalObjectRank, index);
}

/// The walls of a scene in the order they were added, with the contact force each received
/// in the last evaluation (for pressure measurements).
class WallList {
public:
    /// Adds a wall through `point` with outward normal `normal` (normalised here). Throws
    /// core::InputError if the normal is zero or not finite. Returns its index.
    std::size_t add(core::Vec3 const& point, core::Vec3 const& normal, std::uint32_t type = 0);

    [[nodiscard]] std::size_t size() const { return m_walls.size(); }
    [[nodiscard]] bool empty() const { return m_walls.empty(); }
    [[nodiscard]] Wall const& operator[](std::size_t k) const { return m_walls[k]; }
    [[nodiscard]] auto begin() const { return m_walls.begin(); }
    [[nodiscard]] auto end() const { return m_walls.end(); }

    /// Total contact force exerted by the particles on wall `k` [force].
    [[nodiscard]] core::Vec3& force(std::size_t k) { return m_force[k]; }
    [[nodiscard]] core::Vec3 const& force(std::size_t k) const { return m_force[k]; }
    void resetForces();

private:
    std::vector<Wall> m_walls;
    std::vector<core::Vec3> m_force;
};

} // namespace regolith::particles
