#pragma once
/// Walls: a surface (WallShape.hpp) moved rigidly by a function of time (WallMotion.hpp).
/// Global (known on every rank) and few in number, so stored apart from the spheres and
/// tested against every sphere.
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"
#include "particles/storage/WallMotion.hpp"
#include "particles/storage/WallShape.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

/// One wall as it stands at the list's current time (WallList::moveTo).
struct Wall {
    WallGeometry geometry;  ///< the surface now
    WallMotion motion;      ///< how it moves (motion.centre: the axis point at time 0)
    std::uint32_t type = 0; ///< material index into the contact model's MaterialTable
    Uid uid = kInvalidUid;  ///< `wallUid(index)`: the key of its contacts' history
    core::Vec3 centre = core::Vec3::Zero();   ///< the rotation axis point now
    core::Vec3 velocity = core::Vec3::Zero(); ///< the translation velocity now
    bool moving = false; ///< motion.moves(): a fixed wall's contacts skip the motion terms

    /// Signed distance of `x` from the wall surface, positive on the particle side.
    [[nodiscard]] double distance(core::Vec3 const& x) const { return geometry.distance(x); }
    /// The velocity of the wall's material at `x` (a point of the surface) [length/time].
    [[nodiscard]] core::Vec3 surfaceVelocity(core::Vec3 const& x) const {
        return velocity + motion.angularVelocity.cross(x - centre);
    }
};

/// The uid of the wall with index `index`: rank field kGlobalObjectRank, so it never collides
/// with a particle uid.
constexpr Uid wallUid(std::size_t index) {
    return makeUid(kGlobalObjectRank, index);
}

/// What the grains did to one wall.
struct WallLoad {
    core::Vec3 force = core::Vec3::Zero();  ///< contact force on the wall [force]
    core::Vec3 torque = core::Vec3::Zero(); ///< about its centre (Wall::centre) [force length]
    double power = 0.0;                     ///< the wall's power into the grains [energy/time]
};

/// The walls of a scene in the order they were added, with what the grains did to each in the
/// last evaluation and the work each did on the grains since the start (for pressure and
/// energy measurements).
class WallList {
public:
    /// Adds `wall` (its geometry at time 0; directions normalised here, a disc's or cylinder's
    /// edge set to a perpendicular that turns with it, uid = wallUid(index)). Throws
    /// core::InputError naming the wall if a point or direction is not finite, a direction is zero,
    /// a rectangle's edge is parallel to its normal, or a size or radius is not positive. Returns
    /// its index.
    std::size_t add(Wall wall);
    /// Adds a fixed plane through `point` with outward normal `normal`.
    std::size_t add(core::Vec3 const& point, core::Vec3 const& normal, std::uint32_t type = 0);

    [[nodiscard]] std::size_t size() const { return m_walls.size(); }
    [[nodiscard]] bool empty() const { return m_walls.empty(); }
    [[nodiscard]] Wall const& operator[](std::size_t k) const { return m_walls[k]; }
    [[nodiscard]] auto begin() const { return m_walls.begin(); }
    [[nodiscard]] auto end() const { return m_walls.end(); }

    /// Puts every moving wall where its motion has it at time `t`.
    void moveTo(double t);
    /// Whether any wall moves.
    [[nodiscard]] bool moving() const { return m_moving; }

    /// Adds the reaction of one contact on wall `k`: `force` and `couple` acted on the grain
    /// at `point`; the wall takes the opposite.
    void addReaction(std::size_t k, core::Vec3 const& point, core::Vec3 const& force,
                     core::Vec3 const& couple) {
        Wall const& w = m_walls[k];
        WallLoad& load = m_load[k];
        load.force -= force;
        load.torque -= (point - w.centre).cross(force) + couple;
        if (w.moving)
            load.power +=
                force.dot(w.surfaceVelocity(point)) + couple.dot(w.motion.angularVelocity);
    }
    /// What the grains did to wall `k` in the last evaluation (this rank's share).
    [[nodiscard]] WallLoad const& load(std::size_t k) const { return m_load[k]; }
    /// Total contact force exerted by the particles on wall `k` [force].
    [[nodiscard]] core::Vec3 const& force(std::size_t k) const { return m_load[k].force; }
    void resetForces();
    /// Adds a step of length `dt` to every wall's work: the trapezoid of the power before the
    /// step's evaluation and after it (second order, as velocity Verlet).
    void addWork(double dt);
    /// Forgets the power before: the next addWork starts from the last evaluation's.
    void restartWork();
    /// Work wall `k` did on the grains since construction (this rank's share) [energy].
    [[nodiscard]] double work(std::size_t k) const { return m_work[k]; }

private:
    std::vector<Wall> m_walls;
    std::vector<WallGeometry> m_start; ///< every wall's geometry at time 0
    std::vector<WallLoad> m_load;
    std::vector<double> m_powerBefore;
    std::vector<double> m_work;
    bool m_moving = false;
};

} // namespace regolith::particles
