#pragma once
/// The spin-up: a uniform angular acceleration alpha about an axis n through the pile's
/// centre c, applied as the body force f_i = m_i alpha n x (x_i - c) on every master within
/// `reach` of c. Summed over a rigid body it is the torque I alpha about n and no net force
/// (sum m_i (x_i - c) = 0 about the centre of mass), so the pile spins up at d omega / dt =
/// alpha without being pushed. It is the Euler force of a frame spun up at alpha, with the
/// sign reversed, applied in the inertial frame: no centrifugal or Coriolis terms to add, and
/// grains beyond `reach` (shed) move freely. YORP acts on the surface; spread over the volume
/// it needs no surface model, and at a rate slow against 1 / omega_c the pile does not tell
/// the difference.
#include "core/math/Vec3.hpp"
#include "particles/sync/BlockParticles.hpp"

namespace regolith::apps {

/// Adds m_i alpha n x (x_i - c) to the force of each master within `reach` of `centre`
/// (n = `axis`, a unit vector). Not collective.
void addSpinUpTorque(particles::LocalParticles& grains, core::Vec3 const& centre,
                     core::Vec3 const& axis, double alpha, double reach);

} // namespace regolith::apps
