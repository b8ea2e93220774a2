#pragma once
/// The orientation update shared by the integrators: one grain (rotate) or every moving master
/// of a storage in vectorised batches (rotateMoving), with the same bits either way.
#include "core/math/Vec3.hpp"
#include "particles/storage/ParticleStorage.hpp"

namespace regolith::particles {

/// Rotates `q` by the rotation vector `angularVelocity * dt` (world frame), exactly: q <-
/// exp(w dt / 2) q as the quaternion of angle |w| dt about w / |w|, then renormalised when
/// round-off has moved |q|^2 more than 1e-14 from 1.
void rotate(core::Quat& q, core::Vec3 const& angularVelocity, double dt);

/// rotate() for every master of `ps` that moves (neither Shadow nor Fixed), with its angular
/// velocity: batches of grains in structure-of-arrays lanes that the compiler vectorises, the
/// rare lanes with a zero or large angle or a normalisation finished by rotate(). Same bits as
/// rotate() grain by grain.
void rotateMoving(ParticleStorage& ps, double dt);

} // namespace regolith::particles
