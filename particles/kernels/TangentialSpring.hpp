#pragma once
/// Pieces shared by the contact models: the tangential spring with Coulomb limit and the
/// constant-torque rolling resistance.
#include "core/math/Vec3.hpp"
#include "particles/kernels/ContactState.hpp"

namespace regolith::particles {

/// Rotates `spring` into the plane normal to the unit vector `normal`, keeping its length, so
/// that a spring stored in last step's tangent plane follows the rotation of the contact
/// (LAMMPS pair gran/hooke/history, "rotate shear displacements"; Silbert et al., Phys. Rev. E
/// 64 (2001) 051302). A spring along the normal (degenerate) is dropped.
void projectSpring(core::Vec3& spring, core::Vec3 const& normal);

/// The tangential force of a spring-dashpot with Coulomb limit (Cundall & Strack,
/// Geotechnique 29 (1979) 47), acting on j; updates `spring` in place.
///
/// The spring is first rotated into the current tangent plane (projectSpring), then grows by
/// `tangentialVelocity * dt`; the trial force is -kt * spring - ct * tangentialVelocity. If its
/// magnitude exceeds `limit` (mu |F_n|), the force is scaled down to `limit` and the spring is
/// truncated to what that force implies, spring = -(F + ct v_t) / kt (sliding). With
/// kt = 0 or limit = 0 the spring is reset.
/// Units: kt [force/length], ct [force time/length], limit [force], dt [time].
core::Vec3 tangentialForce(core::Vec3& spring, core::Vec3 const& normal,
                           core::Vec3 const& tangentialVelocity, double kt, double ct, double limit,
                           double dt);

/// Constant-torque rolling resistance (Ai, Chen, Rotter & Ooi, Powder Technol. 206 (2011)
/// 269, model A): a couple of magnitude mu_r * R_eff * max(F_n, 0) on j opposing the rolling
/// part of omega_j - omega_i (the component normal to the contact normal; twisting is not
/// resisted). Its magnitude is capped at what would stop the relative rolling within `dt`,
/// the usual fix for model A's chattering around zero rolling velocity.
core::Vec3 rollingTorque(ContactState const& s, double rollingFriction, double normalForce,
                         double dt);

} // namespace regolith::particles
