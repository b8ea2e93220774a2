#include "particles/kernels/ContactEvaluation.hpp"

namespace regolith::particles {

ContactState pairState(ParticleStorage const& ps, Contact const& c) {
    core::Vec3 const ri = c.point - ps.position(c.i);
    core::Vec3 const rj = c.point - ps.position(c.j);
    core::Vec3 const vi = ps.velocity(c.i) + ps.angularVelocity(c.i).cross(ri);
    core::Vec3 const vj = ps.velocity(c.j) + ps.angularVelocity(c.j).cross(rj);
    double const a = ps.radius(c.i), b = ps.radius(c.j);
    return ContactState{c.normal,
                        c.penetration,
                        vj - vi,
                        ps.angularVelocity(c.j) - ps.angularVelocity(c.i),
                        1.0 / (ps.invMass(c.i) + ps.invMass(c.j)),
                        a * b / (a + b),
                        ps.invInertia(c.i) + ps.invInertia(c.j),
                        ps.type(c.i),
                        ps.type(c.j)};
}

ContactState wallState(ParticleStorage const& ps, WallList const& walls, WallContact const& c) {
    std::size_t const k = c.particle;
    core::Vec3 const r = c.point - ps.position(k);
    return ContactState{c.normal,
                        c.penetration,
                        ps.velocity(k) + ps.angularVelocity(k).cross(r),
                        ps.angularVelocity(k),
                        1.0 / ps.invMass(k),
                        ps.radius(k),
                        ps.invInertia(k),
                        walls[c.wall].type,
                        ps.type(k)};
}

void pruneHistory(ParticleStorage& ps, std::uint32_t stamp) {
    for (std::size_t k = 0, n = ps.size(); k < n; ++k)
        if (!ps.history(k).empty())
            ps.history(k).keepOnly(stamp);
}

} // namespace regolith::particles
