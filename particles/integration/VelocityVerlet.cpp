#include "particles/integration/VelocityVerlet.hpp"

namespace regolith::particles {

namespace {
bool moves(Flags f) {
    return !f.isShadow() && !f.isFixed();
}
} // namespace

namespace {

/// `Kicks` half kicks with the current forces (1: preForce's; 2: postForce's and then the
/// next preForce's, in that order, so the same bits as the two calls), then the drift; returns
/// the largest distance a copy moved.
template <int Kicks>
double kickAndDrift(ParticleStorage& ps, double dt, core::Vec3 const& gravity, bool orientation) {
    std::size_t const n = ps.size();
    if (n == 0)
        return 0.0;
    // The arrays' addresses in locals: Eigen's vector stores may alias anything, so through
    // the storage's accessors every grain reloaded them (this pass is a fifth of a sparse
    // gas's step).
    Flags const* const flags = ps.allFlags().data();
    double const* const invMass = ps.invMasses().data();
    double const* const invInertia = ps.invInertias().data();
    core::Vec3 const* const force = &ps.force(0);
    core::Vec3 const* const torque = &ps.torque(0);
    core::Vec3* const position = &ps.position(0);
    core::Vec3* const velocity = &ps.velocity(0);
    core::Vec3* const angularVelocity = &ps.angularVelocity(0);
    double const h = 0.5 * dt;
    LargestMove largest;
    for (std::size_t i = 0; i < n; ++i) {
        if (!moves(flags[i]))
            continue;
        core::Vec3 const kick = h * (invMass[i] * force[i] + gravity);
        core::Vec3 const spin = h * invInertia[i] * torque[i];
        core::Vec3 v = velocity[i];
        core::Vec3 w = angularVelocity[i];
        for (int k = 0; k < Kicks; ++k) {
            v += kick;
            w += spin;
        }
        core::Vec3 const before = position[i];
        core::Vec3 const after = before + dt * v;
        velocity[i] = v;
        position[i] = after;
        angularVelocity[i] = w;
        largest.add(before, after);
    }
    // With the half-step angular velocity, in batches (the rotation was a quarter of a gas
    // step when done grain by grain in the loop above).
    if (orientation)
        rotateMoving(ps, dt);
    return largest.distance();
}

} // namespace

double VelocityVerlet::preForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    return kickAndDrift<1>(ps, dt, gravity, orientation);
}

double VelocityVerlet::postThenPreForce(ParticleStorage& ps, double dt,
                                        core::Vec3 const& gravity) const {
    return kickAndDrift<2>(ps, dt, gravity, orientation);
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
