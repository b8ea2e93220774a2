#pragma once
/// The integrator concept; the rotation update the integrators share is in Rotation.hpp.
#include "core/math/Vec3.hpp"
#include "particles/integration/Rotation.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <concepts>

namespace regolith::particles {

/// A time integrator split around the force computation, so that one loop serves every
/// scheme (mesa_pd's VelocityVerletPreForceUpdate / PostForceUpdate):
///
///     integrator.preForce(ps, dt, g);   // uses the forces of the previous step
///     ps.resetForces(); detect; evaluateContacts; (reduce shadow forces to masters)
///     integrator.postForce(ps, dt, g);  // uses the new forces
///
/// Both move only masters that are not Fixed; `gravity` is an acceleration [length/time^2].
/// Forces must survive from postForce to the next preForce (they travel with a migrating
/// particle).
template <class I>
concept Integrator = requires(I const& integrator, ParticleStorage& ps, double dt,
                              core::Vec3 const& gravity) {
    integrator.preForce(ps, dt, gravity);
    integrator.postForce(ps, dt, gravity);
};

} // namespace regolith::particles
