#include "particles/kernels/ContactEvaluation.hpp"

#include <algorithm>
#include <tuple>

namespace regolith::particles {

ContactState pairState(ParticleStorage const& ps, Contact const& c) {
    core::Vec3 const ri = c.point - ps.position(c.i);
    core::Vec3 const rj = c.point - partnerCentre(ps, c);
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
