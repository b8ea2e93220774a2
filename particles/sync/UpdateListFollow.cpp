// UpdateList::followLeavers: after a call that synchronised only the masters that left their
// blocks, the list catches up with the slots that call wrote, as the Verlet list follows the
// storage (VerletList::follow), instead of deciding every copy again (UpdateList::rebuild).
#include "particles/sync/UpdateList.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

namespace regolith::particles {

bool UpdateList::followLeavers(LocalParticles const& local, core::CommStats& stats) {
    BlocksById const byId = blocksById(local);
    std::vector<std::vector<Key>> keys(m_from.size());
    if (!m_valid || !followStorages(local, byId, keys)) {
        rebuild(local, budgetLeft(), stats);
        return false;
    }
    m_followedMove = m_largestMove;
    m_idleLength = kIdleCalls;
    if (m_exchange)
        m_valid = exchangeKeys(local, byId, keys, stats);
    return true;
}

bool UpdateList::followStorages(LocalParticles const& local, BlocksById const& byId,
                                std::vector<std::vector<Key>>& keys) {
    auto const blocks = local.blocks();
    if (blocks.size() != m_blocks.size() || m_leavers.size() != blocks.size())
        return false;
    int const rank = m_comm.rank();
    // Per block, the slots the call wrote (added, removed, moved or re-keyed a copy in) and the
    // leavers' (a master that left may keep its slot as a shadow), ascending. A copy in any
    // other slot is the one the list knew, with the same key and class: the synchronisation
    // changes a copy's key or class only by removing and adding it.
    std::vector<std::vector<std::uint32_t>> written(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage const& ps = blocks[b].particles;
        if (!ps.tracing() || ps.traceBroken())
            return false;
        auto& w = written[b];
        for (TraceChange const& c : ps.traceJournal())
            w.push_back(c.index);
        w.insert(w.end(), m_leavers[b].begin(), m_leavers[b].end());
        std::sort(w.begin(), w.end());
        w.erase(std::unique(w.begin(), w.end()), w.end());
    }
    // A mark per slot: the shadows' loop below asks twice per shadow.
    std::vector<std::vector<std::uint8_t>> writtenMark(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        writtenMark[b].assign(blocks[b].particles.size(), 0);
        for (std::uint32_t i : written[b])
            if (i < writtenMark[b].size())
                writtenMark[b][i] = 1;
    }
    auto const changed = [&](std::size_t b, std::uint32_t i) {
        return i >= writtenMark[b].size() || writtenMark[b][i] != 0;
    };
    // The copies decided again: every written slot, and the shadows whose master may have moved
    // (a local master's slot was written; a remote one's owner or class changed in place).
    std::vector<std::vector<std::uint32_t>> again(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b)
        for (std::uint32_t i : written[b])
            if (i < blocks[b].particles.size())
                again[b].push_back(i);
    std::vector<std::vector<CopyAt>> from(m_from.size());
    for (std::size_t p = 0; p < m_from.size(); ++p)
        for (CopyAt const& c : m_from[p]) {
            if (changed(c.block, c.index))
                continue;
            ParticleStorage const& ps = blocks[c.block].particles;
            Flags const f = ps.flags(c.index);
            if (f.isShadow() && !f.has(Flag::Spreads) &&
                ps.owner(c.index).rank == m_exchange->peers()[p])
                from[p].push_back(c);
            else
                again[c.block].push_back(c.index);
        }
    std::vector<std::vector<CopyAt>> arrived(m_from.size()); // remote shadows decided again
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage const& ps = blocks[b].particles;
        BlockState& s = m_blocks[b];
        std::vector<Shadow> kept;
        kept.reserve(s.shadows.size());
        for (Shadow const& sh : s.shadows) {
            if (changed(b, sh.index))
                continue;
            if (changed(sh.masterBlock, sh.master))
                again[b].push_back(sh.index);
            else
                kept.push_back(sh);
        }
        std::erase_if(s.nearFaces, [&](std::uint32_t i) { return changed(b, i); });
        auto& a = again[b];
        std::sort(a.begin(), a.end());
        a.erase(std::unique(a.begin(), a.end()), a.end());
        // Each as rebuild() decides it; a master at its position now, with the whole budget
        // (the leavers' call decided it there with the whole skin, and m_budget <= the skin).
        s.reference.resize(ps.size());
        std::vector<Shadow> found;
        std::vector<std::uint32_t> near;
        core::AABB const& box = blocks[b].block->aabb;
        for (std::uint32_t i : a) {
            s.reference[i] = ps.position(i);
            if (ps.flags(i).has(Flag::Spreads))
                return false;
            if (!ps.flags(i).isShadow()) {
                if (mayLeave(box, ps.position(i), m_budget))
                    near.push_back(i);
                continue;
            }
            BlockRef const owner = ps.owner(i);
            if (owner.rank != rank) {
                int const p = peerSlot(owner.rank);
                if (p < 0)
                    return false;
                arrived[static_cast<std::size_t>(p)].push_back({static_cast<std::uint32_t>(b), i});
                continue;
            }
            Shadow shadow{i, 0, 0};
            if (!findMaster(local, byId, owner.block, ps.uid(i), shadow.masterBlock, shadow.master))
                return false;
            found.push_back(shadow);
        }
        // Storage order, as rebuild() lists them (the reduction's sums depend on it).
        s.shadows.clear();
        std::merge(kept.begin(), kept.end(), found.begin(), found.end(),
                   std::back_inserter(s.shadows),
                   [](Shadow const& x, Shadow const& y) { return x.index < y.index; });
        std::vector<std::uint32_t> faces;
        std::merge(s.nearFaces.begin(), s.nearFaces.end(), near.begin(), near.end(),
                   std::back_inserter(faces));
        s.nearFaces = std::move(faces);
        s.revision = ps.layoutRevision();
    }
    auto const before = [](CopyAt const& x, CopyAt const& y) {
        return x.block != y.block ? x.block < y.block : x.index < y.index;
    };
    for (std::size_t p = 0; p < m_from.size(); ++p) {
        m_from[p].clear();
        std::merge(from[p].begin(), from[p].end(), arrived[p].begin(), arrived[p].end(),
                   std::back_inserter(m_from[p]), before);
        for (CopyAt const& c : m_from[p]) {
            ParticleStorage const& ps = blocks[c.block].particles;
            keys[p].push_back({ps.owner(c.index).block, ps.uid(c.index)});
        }
    }
    return true;
}

} // namespace regolith::particles
