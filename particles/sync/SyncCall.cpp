// ParticleSync::sync: one call, along the update list of a sync skin where it holds, for the
// masters that left their blocks only, or in full (UpdateList.hpp, docs/sync.md).
#include "core/Error.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/UpdateList.hpp"

namespace regolith::particles {

SyncVerdict ParticleSync::verdictHere(LocalParticles const& local, double movedAtMost) {
    return m_updateList ? m_updateList->check(local, movedAtMost) : SyncVerdict::Refresh;
}

void ParticleSync::sync(LocalParticles& local, double movedAtMost) {
    SyncVerdict const own = verdictHere(local, movedAtMost);
    syncOn(local, m_updateList ? m_updateList->agree(own) : own);
}

void ParticleSync::shareHistoriesAgain(LocalParticles& local) {
    // The call's Alg. 1 left the shadows that shared a history with it (syncInFull): shared
    // again, or, where the list broke (a copy became SOS class), given their masters'.
    if (!m_updateList->shareHistories(local))
        for (BlockParticles& bp : local.blocks())
            bp.particles.copyMastersHistoriesToShadows();
}

void ParticleSync::syncOn(LocalParticles& local, SyncVerdict verdict) {
    // Every rank acts on the same verdict: a refresh and the leavers' Alg. 1 are collective.
    if (!m_updateList && verdict != SyncVerdict::Refresh)
        throw core::Error("sync: a verdict along an update list, but there is none");
    if (verdict == SyncVerdict::Holds) {
        m_last = SyncStats{};
        m_last.updated = m_updateList->update(local, m_last.comm);
        m_last.alongList = true;
        m_counters.record(m_last.comm);
        return;
    }
    if (verdict == SyncVerdict::Leavers) {
        // Every shadow along the list while the indices hold, then Alg. 1 for the masters
        // that left their blocks only; the others keep their shadows on what budget is left.
        core::CommStats along;
        std::size_t const updated = m_updateList->update(local, along);
        syncInFull(local, m_updateList->leavers(), m_config.skin);
        m_last.updated += updated;
        m_last.leaversOnly = true;
        m_last.listFollowed = m_updateList->followLeavers(local, along);
        shareHistoriesAgain(local);
        m_last.comm += along;
        m_counters.record(along);
        return;
    }
    if (verdict == SyncVerdict::Idle) {
        // An SOS-class copy somewhere: a list would not hold, so neither growth (more shadows)
        // nor a refresh (a pass and a key exchange) would pay. The list retries later. A rank
        // whose own list held may have shared histories: they are not shared again after this
        // call, so its shadows take their own copies first.
        for (BlockParticles& bp : local.blocks())
            bp.particles.stopSharingHistories();
        syncInFull(local, {}, 0.0);
        m_updateList->invalidate();
        m_last.skinIdle = true;
        return;
    }
    syncInFull(local, {}, m_config.skin);
    if (m_updateList) {
        core::CommStats keys;
        m_updateList->rebuild(local, m_config.skin, keys);
        shareHistoriesAgain(local);
        m_last.comm += keys;
        m_counters.record(keys);
    }
}

} // namespace regolith::particles
