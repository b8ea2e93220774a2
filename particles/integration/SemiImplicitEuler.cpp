#include "particles/integration/SemiImplicitEuler.hpp"

namespace regolith::particles {

double SemiImplicitEuler::postForce(ParticleStorage& ps, double dt,
                                    core::Vec3 const& gravity) const {
    LargestMove largest;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        Flags const f = ps.flags(i);
        if (f.isShadow() || f.isFixed())
            continue;
        ps.velocity(i) += dt * (ps.invMass(i) * ps.force(i) + gravity);
        core::Vec3 const before = ps.position(i);
        ps.position(i) += dt * ps.velocity(i);
        largest.add(before, ps.position(i));
        // A sphere's inertia is isotropic, so there is no gyroscopic term: dw/dt = tau / I.
        ps.angularVelocity(i) += dt * ps.invInertia(i) * ps.torque(i);
    }
    rotateMoving(ps, dt); // with the new angular velocity
    return largest.distance();
}

} // namespace regolith::particles
