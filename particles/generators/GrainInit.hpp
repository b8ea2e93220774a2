#pragma once
/// The output of the `[[particles]]` generators: one grain of the initial state as plain data,
/// independent of the particle storage (turned into a ParticleInit by whoever fills it).
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"

#include <cstdint>
#include <functional>

namespace regolith::particles {

struct GrainInit {
    /// Unique over the scene and independent of ranks and blocks: the entry's uid offset plus
    /// the grain's index in the entry's generation order (see generateGrains). Fits the
    /// counter field of a Uid (< 2^kUidCounterBits), i.e. it reads as made by rank 0.
    Uid uid = kInvalidUid;
    core::Vec3 position = core::Vec3::Zero();        ///< centre [length], inside the domain
    core::Vec3 velocity = core::Vec3::Zero();        ///< [length/time]
    core::Vec3 angularVelocity = core::Vec3::Zero(); ///< [rad/time]
    double radius = 0.0;                             ///< [length]
    double density = 0.0;                            ///< [mass/length^3]
    double mass = 0.0;                               ///< [mass], density * 4/3 pi r^3
    std::uint32_t type = 0;                          ///< material index (ParticleSpec::type)
    std::uint32_t entry = 0;                         ///< index of the [[particles]] entry
    bool fixed = false;                              ///< held in place (ParticleSpec::fixed)
};

/// Receives generated grains one at a time (generateGrains, EntrySource): the grains go
/// straight to their consumer (a particle storage) instead of into a list of GrainInit
/// records, which would double the set-up's memory (112 bytes per grain).
using GrainSink = std::function<void(GrainInit const&)>;

/// Mass of a homogeneous sphere, 4/3 pi r^3 density, computed the same way everywhere so
/// that every rank gets bit-identical masses.
[[nodiscard]] double sphereMass(double radius, double density);

} // namespace regolith::particles
