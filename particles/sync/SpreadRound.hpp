#pragma once
/// The second round of SOS (Eibl & Ruede 2018, Alg. 2 lines 15-28): every SOS-class copy of a
/// block orders copies on the neighbour blocks its ball newly overlaps and drops itself where
/// it no longer touches its block.
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

namespace regolith::particles::sync_detail {

/// Writes the round's records for the SOS-class copies of `bp` (creation orders, holder
/// notices, cache notices) into the engine's buffers and removes the shadows of `bp` that no
/// longer overlap it. Visits the SOS-class shadows and the masters in `bp.spreadingMasters`
/// (consumed): the caller lists there every SOS-class master that is not deep inside. Local;
/// the caller exchanges the buffers (receiveRound).
/// Every ball is grown by `halfReach` (half of SyncConfig::reach).
void spread(ParticleSync::Impl& engine, BlockParticles& bp, double halfReach, SyncStats& stats);

} // namespace regolith::particles::sync_detail

namespace regolith::particles {
using sync_detail::spread;
} // namespace regolith::particles
