#pragma once
/// Velocity Verlet in kick-drift-kick form (Swope, Andersen, Berens & Wilson, J. Chem. Phys.
/// 76 (1982) 637): second order and symplectic for position-dependent forces; velocity
/// dependent (damping) forces see the half-step velocity.
#include "particles/integration/Integrator.hpp"

namespace regolith::particles {

struct VelocityVerlet {
    /// Integrate the orientation quaternions (the default). A sphere's orientation enters no
    /// force, no contact and no other grain's motion; it is output only (checkpoints, the state
    /// checksum). A run whose output needs no orientation may switch it off (scene key
    /// time.orientation = false): the orientations then stay as they were, every other bit of
    /// the trajectory is the same, and the update costs no quaternion product per grain and
    /// step (LAMMPS's fix nve/sphere keeps no orientation at all).
    bool orientation = true;

    /// Half kick with the old forces, then drift: v += dt/2 (F/m + g); x += dt v;
    /// omega += dt/2 tau / I; q rotated by omega dt (if `orientation`).
    /// Returns the largest distance a copy moved (Integrator).
    double preForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const;
    /// Second half kick with the new forces: v += dt/2 (F/m + g); omega += dt/2 tau / I.
    /// Returns 0: nothing moves here.
    double postForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const;
    /// postForce, then the next step's preForce, in one pass over the grains: the forces
    /// are the same for both (nothing changes them in between), so each grain's state is read
    /// and written once instead of twice; the same bits as the two calls. The velocities
    /// of the step in between (v(t)) are never stored. Returns what preForce returns.
    double postThenPreForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const;
};

static_assert(Integrator<VelocityVerlet>);

} // namespace regolith::particles
