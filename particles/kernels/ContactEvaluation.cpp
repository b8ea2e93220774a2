#include "particles/kernels/ContactEvaluation.hpp"

#include <algorithm>
#include <tuple>

namespace regolith::particles {

ContactState wallState(ParticleStorage const& ps, WallList const& walls, WallContact const& c) {
    std::size_t const k = c.particle;
    Wall const& wall = walls[c.wall];
    core::Vec3 const r = c.point - ps.position(k);
    core::Vec3 velocity = ps.velocity(k) + ps.angularVelocity(k).cross(r);
    core::Vec3 omega = ps.angularVelocity(k);
    if (wall.moving) { // relative to the wall's material
        velocity -= wall.surfaceVelocity(c.point);
        omega -= wall.motion.angularVelocity;
    }
    return ContactState{c.normal,     c.penetration,    velocity,  omega,     1.0 / ps.invMass(k),
                        ps.radius(k), ps.invInertia(k), wall.type, ps.type(k)};
}

bool recordOrder(ParticleStorage const& ps, ForceRecord const& a, ForceRecord const& b) {
    if (a.copy != b.copy) {
        auto const ka = ps.key(a.copy), kb = ps.key(b.copy);
        if (ka != kb)
            return ka < kb;
    }
    return partnerOrder(a, b);
}

void sumRecords(std::vector<ForceRecord>& records, ParticleStorage& ps) {
    std::sort(records.begin(), records.end(),
              [&ps](ForceRecord const& a, ForceRecord const& b) { return recordOrder(ps, a, b); });
    for (ForceRecord const& r : records) {
        ps.force(r.copy) += r.force;
        ps.torque(r.copy) += r.torque;
    }
}

void pruneHistory(ParticleStorage& ps, std::uint32_t stamp) {
    for (std::size_t k = 0, n = ps.size(); k < n; ++k)
        if (!ps.history(k).empty())
            ps.history(k).keepOnly(stamp);
}

} // namespace regolith::particles
