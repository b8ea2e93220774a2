#include "particles/kernels/TangentialSpring.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

void projectSpring(core::Vec3& spring, core::Vec3 const& normal) {
    double const before = spring.squaredNorm();
    if (before == 0.0)
        return;
    spring -= spring.dot(normal) * normal;
    double const after = spring.squaredNorm();
    if (after > 1e-24 * before)
        spring *= std::sqrt(before / after);
    else
        spring.setZero();
}

core::Vec3 tangentialForce(core::Vec3& spring, core::Vec3 const& normal,
                           core::Vec3 const& tangentialVelocity, double kt, double ct, double limit,
                           double dt) {
    if (!(kt > 0.0) || !(limit > 0.0)) {
        spring.setZero();
        return core::Vec3::Zero();
    }
    projectSpring(spring, normal);
    spring += tangentialVelocity * dt;
    core::Vec3 force = -kt * spring - ct * tangentialVelocity;
    double const f2 = force.squaredNorm();
    if (f2 > limit * limit) {
        force *= limit / std::sqrt(f2);
        spring = -(force + ct * tangentialVelocity) / kt;
    }
    return force;
}

core::Vec3 rollingTorque(ContactState const& s, double rollingFriction, double normalForce,
                         double dt) {
    if (!(rollingFriction > 0.0) || !(normalForce > 0.0))
        return core::Vec3::Zero();
    core::Vec3 const w =
        s.relativeAngularVelocity - s.relativeAngularVelocity.dot(s.normal) * s.normal;
    double const wNorm = w.norm();
    if (wNorm == 0.0)
        return core::Vec3::Zero();
    double magnitude = rollingFriction * s.effectiveRadius * normalForce;
    if (s.inverseInertiaSum > 0.0)
        magnitude = std::min(magnitude, wNorm / (dt * s.inverseInertiaSum));
    return -magnitude / wNorm * w;
}

} // namespace regolith::particles
