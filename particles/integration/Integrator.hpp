#pragma once
/// The integrator concept and the rotation update shared by the integrators.
#include "core/math/Vec3.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <Eigen/Geometry>

#include <cmath>
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

/// Rotates `q` by the rotation vector `angularVelocity * dt` (world frame), exactly: q <-
/// exp(w dt / 2) q as the quaternion of angle |w| dt about w / |w|, then renormalised when
/// round-off has moved |q|^2 more than 1e-14 from 1. Inline: it runs for every grain and step.
inline void rotate(core::Quat& q, core::Vec3 const& angularVelocity, double dt) {
    double const w2 = angularVelocity.squaredNorm();
    if (w2 == 0.0)
        return;
    // The rotation quaternion (cos(a/2), sin(a/2) w/|w|) with a = |w| dt. For the small angles
    // of a DEM step (a < 1e-2) the Taylor series of cos(a/2) and sin(a/2)/|w| to the a^6 term
    // is exact to round-off (the next terms are below a^8/1e7 < 1e-23) and needs no sqrt, sin
    // or cos; larger angles take the closed form.
    double const a2 = w2 * dt * dt;
    double c = 0.0;
    double s = 0.0; // sin(a/2) / |w|
    if (a2 < 1e-4) [[likely]] {
        // Horner form with the reciprocals of 8, 384, 46080 (cos) and 48, 3840, 645120 (sin):
        // multiplications, not five divisions per grain and step.
        c = 1.0 + a2 * (-1.0 / 8.0 + a2 * (1.0 / 384.0 - a2 * (1.0 / 46080.0)));
        s = dt * (0.5 + a2 * (-1.0 / 48.0 + a2 * (1.0 / 3840.0 - a2 * (1.0 / 645120.0))));
    } else {
        double const w = std::sqrt(w2);
        c = std::cos(0.5 * w * dt);
        s = std::sin(0.5 * w * dt) / w;
    }
    core::Quat const r(c, s * angularVelocity.x(), s * angularVelocity.y(),
                       s * angularVelocity.z());
    q = r * q;
    // r is a unit quaternion to round-off, so |q| drifts by a few ulps per step at most: the
    // square root and division of a normalisation are needed only now and then.
    if (std::abs(q.squaredNorm() - 1.0) > 1e-14)
        q.normalize();
}

} // namespace regolith::particles
