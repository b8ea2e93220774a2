#include "particles/integration/VelocityVerlet.hpp"

namespace regolith::particles {

namespace {
bool moves(Flags f) {
    return !f.isShadow() && !f.isFixed();
}
} // namespace

void VelocityVerlet::preForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    double const h = 0.5 * dt;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (!moves(ps.flags(i)))
            continue;
        ps.velocity(i) += h * (ps.invMass(i) * ps.force(i) + gravity);
        ps.position(i) += dt * ps.velocity(i);
        ps.angularVelocity(i) += h * ps.invInertia(i) * ps.torque(i);
    }
    // With the half-step angular velocity, in batches (the rotation was a quarter of a gas
    // step when done grain by grain in the loop above).
    if (orientation)
        rotateMoving(ps, dt);
}

void VelocityVerlet::postForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    double const h = 0.5 * dt;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (!moves(ps.flags(i)))
            continue;
        ps.velocity(i) += h * (ps.invMass(i) * ps.force(i) + gravity);
        ps.angularVelocity(i) += h * ps.invInertia(i) * ps.torque(i);
    }
}

} // namespace regolith::particles
