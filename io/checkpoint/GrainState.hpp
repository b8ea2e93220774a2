#pragma once
/// The complete state of one master grain as a checkpoint stores it: everything a restart
/// needs to continue bit for bit (velocity Verlet's first half kick of the next step uses the
/// force and torque of the last step; the tangential springs live in the contact history).
/// Derived quantities (inverse mass and inertia) and the synchronisation's bookkeeping
/// (owner, shadow holders, images) are not stored: they are rebuilt on restart.
#include "core/math/Vec3.hpp"
#include "particles/storage/ContactHistory.hpp"
#include "particles/storage/GrainQuantities.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/Uid.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace regolith::io {

/// The table's entries (particles/storage/GrainQuantities.hpp: the kept state uid, position,
/// ..., flags, and the self-gravity records), the contact history and the declared grain fields.
struct GrainState : particles::GrainRow, particles::GrainGravityRecord {
    std::vector<particles::HistoryEntry> history; ///< in partner uid order
    std::vector<double> fields; ///< the declared grain fields (particles/storage/GrainFields.hpp)
};

/// The masters of every local block, in block order then storage order. Not collective.
[[nodiscard]] std::vector<GrainState> collectMasters(particles::LocalParticles const& local);

/// The grain as a new master (its history is set separately: ParticleInit has no room for
/// it). Not collective.
[[nodiscard]] particles::ParticleInit toParticleInit(GrainState const& g);

/// Copies the contact history of `g` onto particle `i` of `ps`. Not collective.
void restoreHistory(GrainState const& g, particles::ParticleStorage& ps,
                    particles::ParticleStorage::Index i);

/// A 64-bit hash of every stored field of `g` (FNV-1a over the values' bytes, finalised with
/// a 64-bit mixer), the term of the order-independent checkpoint checksum (a sum of terms,
/// so any rank may hash any slice). Not collective.
[[nodiscard]] std::uint64_t grainHash(GrainState const& g);

/// FNV-1a over `bytes`, continuing from `seed` (the FNV offset basis by default).
[[nodiscard]] std::uint64_t fnv1a(std::span<std::byte const> bytes,
                                  std::uint64_t seed = 0xCBF29CE484222325ULL);

} // namespace regolith::io
