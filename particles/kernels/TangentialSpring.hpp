#pragma once
/// Pieces shared by the contact models: the tangential spring with Coulomb limit and the
/// rolling resistance (constant torque, model A, or spring-dashpot-slider, model C). Inline: they
/// run once per contact and step, inside the models' operator(), which the fused contact loop
/// inlines too.
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

/// What a sliding contact's spring is truncated to (tangentialForce).
enum class SlipTruncation {
    /// spring = -(F + c_t v_t) / k_t: the spring and the dashpot together give the capped
    /// force F (LAMMPS pair gran/hooke/history). Right where k_t and c_t are constant.
    SpringAndDashpot,
    /// spring = -F / k_t: the spring alone gives F, the dashpot is dropped while sliding
    /// (LIGGGHTS). Needed where k_t grows with the overlap faster than c_t (Hertz: k_t ~ a,
    /// c_t ~ sqrt(a)): the dashpot's share kept in the spring would turn into an elastic force
    /// along the slip as the contact loads (friction would push a sliding sphere forward, and
    /// model C's rolling couple would add spin).
    SpringOnly,
};

/// The tangential force of a spring-dashpot with Coulomb limit (Cundall & Strack,
/// Geotechnique 29 (1979) 47), acting on j; updates `spring` in place.
///
/// The spring is first rotated into the current tangent plane (projectSpring), then grows by
/// `tangentialVelocity * dt`; the trial force is -kt * spring - ct * tangentialVelocity. If its
/// magnitude exceeds `limit` (mu |F_n|), the force is scaled down to `limit` and the spring is
/// truncated to what that force implies (sliding; `truncation`). With kt = 0 or limit = 0 the
/// spring is reset.
/// Units: kt [force/length], ct [force time/length], limit [force], dt [time].
inline core::Vec3 tangentialForce(core::Vec3& spring, core::Vec3 const& normal,
                                  core::Vec3 const& tangentialVelocity, double kt, double ct,
                                  double limit, double dt,
                                  SlipTruncation truncation = SlipTruncation::SpringAndDashpot) {
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
        spring = truncation == SlipTruncation::SpringAndDashpot
                     ? core::Vec3(-(force + ct * tangentialVelocity) / kt)
                     : core::Vec3(-force / kt);
    }
    return force;
}

/// Constant-torque rolling resistance (Ai, Chen, Rotter & Ooi, Powder Technol. 206 (2011)
/// 269, model A): a couple of magnitude mu_r * R_eff * max(F_n, 0) on j opposing the rolling
/// part of omega_j - omega_i (the component normal to the contact normal; twisting is not
/// resisted). Its magnitude is capped at what would stop the relative rolling within `dt`,
/// the usual fix for model A's chattering around zero rolling velocity. Known limit: it
/// cannot hold a grain at rest against a driving torque T, which creeps at the relative spin
/// T dt ΣI⁻¹ (docs/notes/contact-models.md); model C
/// (rollingSpringTorque) does.
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

/// Model C's parameters for one pair of materials (rollingSpringTorque); off: model A.
struct RollingSpring {
    bool enabled = false;
    /// k_r [force/length] on the rolling displacement; 0: Ai et al.'s 2.25 mu_r^2 k_n (their
    /// eq. 18 written for a displacement, k_n the normal stiffness of the contact), at most
    /// k_n (MaterialCheck::rollingSpring).
    double stiffness = 0.0;
    /// eta_r: c_r = 2 eta_r sqrt(k_r m_r), m_r = 1 / (R_eff^2 Σ 1/(I + m r^2)) the inertia
    /// of the relative rolling about the contact point, as Ai et al. take it (they recommend
    /// 0.3); for solid spheres I + m r^2 = 3.5 I.
    double dampingRatio = 0.3;
};

/// Spring-dashpot-slider rolling resistance (Ai, Chen, Rotter & Ooi, Powder Technol. 206
/// (2011) 269, model C; the displacement form of LAMMPS's pair granular `rolling sds`), the
/// couple on j; updates `rolling` in place. The relative rolling velocity
/// v_r = R_eff (omega_j - omega_i) x n (twisting about n is not resisted) accumulates in
/// `rolling`, kept in the tangent plane like the tangential spring (projectSpring); the trial
/// force f = -k_r rolling - c_r v_r is capped at mu_r max(F_n, 0), the spring truncated to what
/// the cap implies (the slider), and the couple is R_eff n x f, so at most mu_r R_eff F_n as in
/// model A. Unlike model A it holds a grain at rest against a driving torque below that cap
/// (tests/particles/InclineTest.cpp). With mu_r = 0, k_r = 0 or F_n <= 0 the spring is reset
/// and there is no couple. k_r is at most k_n, and c_r at most what stops the relative
/// rolling within one step (the explicit step's stability).
/// Units: normalStiffness k_n [force/length] (for the default k_r), normalForce [force].
inline core::Vec3 rollingSpringTorque(ContactState const& s, core::Vec3& rolling,
                                      double rollingFriction, RollingSpring const& law,
                                      double normalStiffness, double normalForce, double dt,
                                      SlipTruncation truncation) {
    // At most the contact's normal stiffness (a given k_r too, for Hertz, whose normal
    // stiffness the scene cannot bound): stiffer, the explicit step would not hold it.
    double const kr =
        std::min(law.stiffness > 0.0 ? law.stiffness
                                     : 2.25 * rollingFriction * rollingFriction * normalStiffness,
                 normalStiffness);
    double const reff = s.effectiveRadius;
    core::Vec3 const vr = reff * s.relativeAngularVelocity.cross(s.normal);
    // Grains are solid spheres (ParticleStorage: I = 2/5 m r^2): about the contact point each
    // inverse inertia is 1/3.5 of the one about the centre. The dashpot acts on the spins,
    // explicitly: capped where it would stop the relative rolling within one step (beyond,
    // it reversed it every step and the couple averaged out: a large damping ratio let a
    // grain roll freely).
    double const rr = reff * reff * s.inverseInertiaSum;
    double const cr =
        s.inverseInertiaSum > 0.0
            ? std::min(2.0 * law.dampingRatio * std::sqrt(3.5 * kr / rr), 1.0 / (rr * dt))
            : 0.0;
    // The same spring-dashpot-slider as the tangential one, on the rolling displacement.
    core::Vec3 const f =
        tangentialForce(rolling, s.normal, vr, kr, cr, rollingFriction * std::max(normalForce, 0.0),
                        dt, truncation);
    return reff * s.normal.cross(f);
}

/// The couple on j of the pair's rolling resistance: model C (rollingSpringTorque, its slider
/// truncated as `truncation` says) if `law` is enabled, else model A (rollingTorque), which
/// leaves `rolling` alone.
inline core::Vec3 rollingResistance(ContactState const& s, core::Vec3& rolling,
                                    double rollingFriction, RollingSpring const& law,
                                    double normalStiffness, double normalForce, double dt,
                                    SlipTruncation truncation = SlipTruncation::SpringAndDashpot) {
    if (law.enabled)
        return rollingSpringTorque(s, rolling, rollingFriction, law, normalStiffness, normalForce,
                                   dt, truncation);
    return rollingTorque(s, rollingFriction, normalForce, dt);
}

} // namespace regolith::particles
