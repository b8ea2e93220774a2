#include "particles/integration/SemiImplicitEuler.hpp"

namespace regolith::particles {

void SemiImplicitEuler::postForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const {
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        Flags const f = ps.flags(i);
        if (f.isShadow() || f.isFixed())
            continue;
        ps.velocity(i) += dt * (ps.invMass(i) * ps.force(i) + gravity);
        ps.position(i) += dt * ps.velocity(i);
        // A sphere's inertia is isotropic, so there is no gyroscopic term: dw/dt = tau / I.
        ps.angularVelocity(i) += dt * ps.invInertia(i) * ps.torque(i);
    }
    rotateMoving(ps, dt); // with the new angular velocity
}

} // namespace regolith::particles
