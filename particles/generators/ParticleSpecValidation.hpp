#pragma once
/// Checks the `[[particles]]` entries before anything is generated. Every rank reads the same
/// scene, so every rank throws the same core::InputError; the message starts with the scene
/// key, e.g. "particles[2].spacing: must be positive, got 0".
#include "particles/generators/GeneratorDomain.hpp"
#include "particles/generators/GeneratorSpec.hpp"

#include <cstddef>
#include <span>
#include <string>

namespace regolith::particles {

/// "particles[i]", the scene key of entry i.
[[nodiscard]] std::string entryKey(std::size_t index);

/// Throws core::InputError unless, for every entry (keys as in GeneratorSpec.hpp):
///  - every length, density and velocity is finite; radius, density, spacing are positive;
///  - lattice: region.min < region.max on every axis and the region lies inside the domain;
///    velocity.random has lo <= hi;
///  - list: radius and velocity hold 1 or one value per position (velocity may be empty);
///    every grain is placed as checkGrainPlacement requires;
///  - file: path is not empty; density, if given, is positive (the file itself is checked
///    when it is read, see generateGrains);
///  - agglomerate: 0 < grain_radius[0] <= grain_radius[1] < radius, count >= 0,
///    max_attempts >= 1, the center lies in the domain and, on non-periodic axes, the whole
///    sphere does;
///  - on a periodic axis every grain diameter is below the period (a grain must not touch
///    its own image);
///  - a radius range (lattice, list) has 0 < min <= max; angular_velocity is finite; a
///    fixed entry gives no velocity or angular velocity other than 0.
/// Also checks the domain itself (finite, min < max). Not collective.
void validateParticleSpecs(std::span<ParticleSpec const> specs, GeneratorDomain const& domain);

/// Throws core::InputError starting with `what` unless the grain (centre, radius) is placed
/// legally: radius positive and finite, centre finite and inside the domain ([min, max) on
/// periodic axes), the whole grain inside the domain on non-periodic axes, and its diameter
/// below the period on periodic axes.
void checkGrainPlacement(core::Vec3 const& centre, double radius, GeneratorDomain const& domain,
                         std::string const& what);

} // namespace regolith::particles
