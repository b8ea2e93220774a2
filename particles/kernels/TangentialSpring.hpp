#pragma once
/// Pieces shared by the contact models: the tangential spring with Coulomb limit and the
/// constant-torque rolling resistance. Inline: they run once per contact and step, inside the
/// models' operator(), which the fused contact loop inlines too.
#include "core/math/Vec3.hpp"
#include "particles/kernels/ContactState.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

/// Rotates `spring` into the plane normal to the unit vector `normal`, keeping its length, so
/// that a spring stored in last step's tangent plane follows the rotation of the contact
/// (LAMMPS pair gran/hooke/history, "rotate shear displacements"; Silbert et al., Phys. Rev. E
/// 64 (2001) 051302). A spring along the normal (degenerate) is dropped.
inline void projectSpring(core::Vec3& spring, core::Vec3 const& normal) {
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

/// The tangential force of a spring-dashpot with Coulomb limit (Cundall & Strack,
/// Geotechnique 29 (1979) 47), acting on j; updates `spring` in place.
///
/// The spring is first rotated into the current tangent plane (projectSpring), then grows by
/// `tangentialVelocity * dt`; the trial force is -kt * spring - ct * tangentialVelocity. If its
/// magnitude exceeds `limit` (mu |F_n|), the force is scaled down to `limit` and the spring is
/// truncated to what that force implies, spring = -(F + ct v_t) / kt (sliding). With
/// kt = 0 or limit = 0 the spring is reset.
/// Units: kt [force/length], ct [force time/length], limit [force], dt [time].
inline core::Vec3 tangentialForce(core::Vec3& spring, core::Vec3 const& normal,
                                  core::Vec3 const& tangentialVelocity, double kt, double ct,
                                  double limit, double dt) {
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

/// Constant-torque rolling resistance (Ai, Chen, Rotter & Ooi, Powder Technol. 206 (2011)
/// 269, model A): a couple of magnitude mu_r * R_eff * max(F_n, 0) on j opposing the rolling
/// part of omega_j - omega_i (the component normal to the contact normal; twisting is not
/// resisted). Its magnitude is capped at what would stop the relative rolling within `dt`,
/// the usual fix for model A's chattering around zero rolling velocity. Known limit: it
/// cannot hold a grain at rest against a driving torque T, which creeps at the relative spin
/// T dt ΣI⁻¹ (docs/results.md, "Known limits of the contact models"); model C's rolling
/// spring would.
inline core::Vec3 rollingTorque(ContactState const& s, double rollingFriction, double normalForce,
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
