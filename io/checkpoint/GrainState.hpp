#pragma once
/// The complete state of one master grain as a checkpoint stores it: everything a restart
/// needs to continue bit for bit (velocity Verlet's first half kick of the next step uses the
/// force and torque of the last step; the tangential springs live in the contact history).
/// Derived quantities (inverse mass and inertia) and the synchronisation's bookkeeping
/// (owner, shadow holders, images) are not stored: they are rebuilt on restart.
#include "core/math/Vec3.hpp"
#include "particles/storage/ContactHistory.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/Uid.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace regolith::io {

struct GrainState {
    particles::Uid uid = particles::kInvalidUid;
    core::Vec3 position = core::Vec3::Zero();        ///< [length]
    core::Vec3 velocity = core::Vec3::Zero();        ///< [length/time]
    core::Vec3 angularVelocity = core::Vec3::Zero(); ///< world frame [rad/time]
    core::Quat orientation = core::Quat::Identity();
    core::Vec3 force = core::Vec3::Zero();        ///< of the last force computation [force]
    core::Vec3 torque = core::Vec3::Zero();       ///< of the last force computation [force length]
    double radius = 0.0;                          ///< [length]
    double mass = 0.0;                            ///< [mass]
    std::uint32_t type = 0;                       ///< material index
    std::uint8_t flags = 0;                       ///< particles::Flags bits (Shadow never set)
    std::vector<particles::HistoryEntry> history; ///< in partner uid order
    /// Self-gravity with update_threshold > 0 or update_every: the grain's position at the last
    /// field update, the acceleration it got then, which it keeps until the next update, and
    /// the rate it is extrapolated at (update_every). NaN if it has none (no self-gravity,
    /// threshold 0 without update_every, or no update yet).
    core::Vec3 gravityReference = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    core::Vec3 gravityField = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    core::Vec3 gravitySlope = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    std::vector<double> fields; ///< the declared grain fields (particles/storage/GrainFields.hpp)
};

/// The masters of every local block, in block order then storage order. Not collective.
[[nodiscard]] std::vector<GrainState> collectMasters(particles::LocalParticles const& local);

/// The grain as a new master (force, torque and history are set separately: ParticleInit
/// has no room for them). Not collective.
[[nodiscard]] particles::ParticleInit toParticleInit(GrainState const& g);

/// Copies force, torque and contact history of `g` onto particle `i` of `ps`. Not collective.
void restoreDynamicState(GrainState const& g, particles::ParticleStorage& ps,
                         particles::ParticleStorage::Index i);

/// A 64-bit hash of every stored field of `g` (FNV-1a over the values' bytes, finalised with
/// a 64-bit mixer), the term of the order-independent checkpoint checksum (a sum of terms,
/// so any rank may hash any slice). Not collective.
[[nodiscard]] std::uint64_t grainHash(GrainState const& g);

/// FNV-1a over `bytes`, continuing from `seed` (the FNV offset basis by default).
[[nodiscard]] std::uint64_t fnv1a(std::span<std::byte const> bytes,
                                  std::uint64_t seed = 0xCBF29CE484222325ULL);

} // namespace regolith::io
