#include "apps/common/ConservedQuantities.hpp"

#include <array>

namespace regolith::apps {

RunSummary::Conserved conservedQuantities(core::Comm const& comm,
                                          std::span<MasterRecord const> local,
                                          core::Vec3 const& gravity) {
    return conservedQuantitiesFrom(comm, sourceOf(local), gravity);
}

RunSummary::Conserved conservedQuantitiesFrom(core::Comm const& comm, MasterSource const& local,
                                              core::Vec3 const& gravity) {
    // One reduction: momentum (3), angular momentum (3), kinetic, potential, mass, m x (3),
    // rotational kinetic.
    std::array<double, 13> sums{};
    local([&](MasterRecord const& m) {
        core::Vec3 const p = m.mass * m.velocity;
        double const inertia = 0.4 * m.mass * m.radius * m.radius;
        core::Vec3 const l = m.position.cross(p) + inertia * m.angularVelocity;
        for (int a = 0; a < 3; ++a) {
            auto const ua = static_cast<std::size_t>(a);
            sums[ua] += p[a];
            sums[3 + ua] += l[a];
            sums[9 + ua] += m.mass * m.position[a];
        }
        double const spin = inertia * m.angularVelocity.squaredNorm();
        sums[6] += 0.5 * (m.mass * m.velocity.squaredNorm() + spin);
        sums[12] += 0.5 * spin;
        sums[7] -= m.mass * gravity.dot(m.position);
        sums[8] += m.mass;
    });
    comm.allReduceInPlace(std::span<double>(sums), core::ReduceOp::Sum);
    RunSummary::Conserved c;
    c.momentum = core::Vec3(sums[0], sums[1], sums[2]);
    c.angularMomentum = core::Vec3(sums[3], sums[4], sums[5]);
    c.kineticEnergy = sums[6];
    c.rotationalEnergy = sums[12];
    c.potentialEnergy = sums[7];
    if (sums[8] > 0.0)
        c.centerOfMass = core::Vec3(sums[9], sums[10], sums[11]) / sums[8];
    c.mass = sums[8];
    return c;
}

} // namespace regolith::apps
