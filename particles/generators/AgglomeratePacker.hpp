#pragma once
/// The grains of a `kind = "agglomerate"` entry: random sequential insertion (RSA; Widom 1966,
/// "Random sequential addition of hard spheres to a volume", J. Chem. Phys. 44, 3888) of
/// spheres with radii uniform in grain_radius into the enclosing sphere, largest first, each
/// grain retrying random positions until it overlaps neither a grain placed before nor a grain
/// of an earlier entry. Inherently serial, so every rank packs the whole agglomerate.
#include "particles/generators/GeneratorDomain.hpp"
#include "particles/generators/GeneratorSpec.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/generators/OverlapIndex.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace regolith::particles {

/// Packs the agglomerate entry `entrySpec` (validated; its kind an AgglomerateSpec `spec`),
/// the entry `entry` of the scene. Grain i (0 <= i < count) gets uid
/// `uidOffset + i`, and draws everything from core::random::CounterRng(spec.seed, uid):
/// first its radius (uniform in [grain_radius[0], grain_radius[1])), then, attempt after
/// attempt, a point uniform in the unit ball (rejection from the cube, x, y, z in order),
/// placing the centre at center + (radius - r) * point so the grain lies inside the sphere.
/// Grains are inserted by decreasing radius (ties by uid); positions are wrapped into the
/// domain on periodic axes and overlap is tested against periodic images. Deterministic for a
/// seed and independent of the rank and block layout.
///
/// Returns `count` grains in uid order with the entry's type, fixed flag and angular velocity
/// w, and the velocity of a rigid body turning about the center, spec.velocity + w x (x - center)
/// (before the wrap; the bulk velocity alone without w).
/// Throws core::InputError naming `key` if sum r^3 / radius^3 >= 1 or a grain finds no free
/// position within spec.maxAttempts attempts; the message states the requested packing
/// fraction. Not collective.
[[nodiscard]] std::vector<GrainInit> packAgglomerate(ParticleSpec const& entrySpec,
                                                     std::uint64_t uidOffset, std::uint32_t entry,
                                                     GeneratorDomain const& domain,
                                                     OverlapIndex const& obstacles,
                                                     std::string const& key);

} // namespace regolith::particles
