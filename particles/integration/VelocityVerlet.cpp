#include "particles/integration/VelocityVerlet.hpp"

namespace regolith::particles {

namespace {
bool moves(Flags f) {
    return !f.isShadow() && !f.isFixed();
}
} // namespace

double VelocityVerlet::preForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    double const h = 0.5 * dt;
    LargestMove largest;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (!moves(ps.flags(i)))
            continue;
        core::Vec3 const v = ps.velocity(i) + h * (ps.invMass(i) * ps.force(i) + gravity);
        core::Vec3 const before = ps.position(i);
        core::Vec3 const after = before + dt * v;
        ps.velocity(i) = v;
        ps.position(i) = after;
        largest.add(before, after);
        ps.angularVelocity(i) += h * ps.invInertia(i) * ps.torque(i);
    }
    // With the half-step angular velocity, in batches (the rotation was a quarter of a gas
    // step when done grain by grain in the loop above).
    if (orientation)
        rotateMoving(ps, dt);
    return largest.distance();
}

double VelocityVerlet::postThenPreForce(ParticleStorage& ps, double dt,
                                        core::Vec3 const& gravity) const {
    double const h = 0.5 * dt;
    LargestMove largest;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (!moves(ps.flags(i)))
            continue;
        // The two half kicks as postForce and preForce do them, in their order (same bits).
        core::Vec3 const kick = h * (ps.invMass(i) * ps.force(i) + gravity);
        core::Vec3 const v = (ps.velocity(i) + kick) + kick;
        core::Vec3 const before = ps.position(i);
        core::Vec3 const after = before + dt * v;
        ps.velocity(i) = v;
        ps.position(i) = after;
        largest.add(before, after);
        core::Vec3 const spin = h * ps.invInertia(i) * ps.torque(i);
        ps.angularVelocity(i) = (ps.angularVelocity(i) + spin) + spin;
    }
    if (orientation)
        rotateMoving(ps, dt);
    return largest.distance();
}

double VelocityVerlet::postForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    double const h = 0.5 * dt;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (!moves(ps.flags(i)))
            continue;
        ps.velocity(i) += h * (ps.invMass(i) * ps.force(i) + gravity);
        ps.angularVelocity(i) += h * ps.invInertia(i) * ps.torque(i);
    }
    return 0.0; // no drift here
}

} // namespace regolith::particles
