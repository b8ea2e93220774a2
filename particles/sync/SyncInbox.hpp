#pragma once
/// Receiving side of one synchronisation round: parses the records of every message and
/// applies them block by block in a fixed order, so the result does not depend on which
/// sender's message came first.
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

namespace regolith::particles::sync_detail {

/// Exchanges the round's buffers and applies what arrives: removals, then updates that
/// re-key a copy (ownership moved across a periodic boundary), in-place updates, promotions,
/// creations (a copy already held is a duplicate and discarded, SOS), then the holder and
/// cache notices. Throws core::Error for a record that contradicts the local state (an
/// update for a copy this block does not hold) or a malformed message. `raiseFlag`: this
/// rank's say in the exchange's flag (ParticleSync::Impl::flagRaised). COLLECTIVE.
void receiveRound(ParticleSync::Impl& engine, LocalParticles& local, SyncStats& stats,
                  bool raiseFlag = false);

/// Drops `bp`'s sent-cache entries of `uid` (its local copy is gone, or it stopped spreading).
void forgetSent(BlockParticles& bp, Uid uid);

} // namespace regolith::particles::sync_detail

namespace regolith::particles {
using sync_detail::forgetSent;
using sync_detail::receiveRound;
} // namespace regolith::particles
