#include "particles/integration/Integrator.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace regolith::particles {

void rotate(core::Quat& q, core::Vec3 const& angularVelocity, double dt) {
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
    if (a2 < 1e-4) {
        c = 1.0 - a2 / 8.0 + a2 * a2 / 384.0 - a2 * a2 * a2 / 46080.0;
        s = dt * (0.5 - a2 / 48.0 + a2 * a2 / 3840.0 - a2 * a2 * a2 / 645120.0);
    } else {
        double const w = std::sqrt(w2);
        c = std::cos(0.5 * w * dt);
        s = std::sin(0.5 * w * dt) / w;
    }
    core::Quat const r(c, s * angularVelocity.x(), s * angularVelocity.y(),
                       s * angularVelocity.z());
    q = r * q;
    q.normalize();
}

} // namespace regolith::particles
