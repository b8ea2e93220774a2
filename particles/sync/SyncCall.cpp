// ParticleSync::sync: one call, along the update list of a sync skin where it holds, for the
// masters that left their blocks only, or in full (UpdateList.hpp, docs/sync.md).
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/UpdateList.hpp"

namespace regolith::particles {

void ParticleSync::sync(LocalParticles& local, double movedAtMost) {
    UpdateList::Verdict const verdict =
        m_updateList ? m_updateList->check(local, movedAtMost) : UpdateList::Verdict::Refresh;
    if (verdict == UpdateList::Verdict::Holds) {
        m_last = SyncStats{};
        m_last.updated = m_updateList->update(local);
        m_last.alongList = true;
        m_counters.record(m_last.comm);
        return;
    }
    if (verdict == UpdateList::Verdict::Leavers) {
        // Every shadow along the list while the indices hold, then Alg. 1 for the masters
        // that left their blocks only; the others keep their shadows on what budget is left.
        std::size_t const updated = m_updateList->update(local);
        syncInFull(local, m_updateList->leavers());
        m_last.updated += updated;
        m_last.leaversOnly = true;
        m_updateList->rebuild(local, m_impl->rank(), m_updateList->budgetLeft());
        return;
    }
    syncInFull(local, {});
    if (m_updateList)
        m_updateList->rebuild(local, m_impl->rank(), m_config.skin);
}

} // namespace regolith::particles
