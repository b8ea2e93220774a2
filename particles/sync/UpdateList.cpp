#include "particles/sync/UpdateList.hpp"

#include "core/Error.hpp"
#include "particles/sync/SyncInbox.hpp"
#include "particles/sync/SyncMessages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace regolith::particles {

/// Within twice the budget of a face (the factor and the relative 1e-9 of the coordinates cover
/// the rounding of the distances; a master outside already, or not finite, counts too).
bool UpdateList::mayLeave(core::AABB const& box, core::Vec3 const& x, double budget) {
    double const toFace = std::min((x - box.min).minCoeff(), (box.max - x).minCoeff());
    double const scale = x.cwiseAbs().maxCoeff() + box.max.cwiseAbs().maxCoeff();
    return !(toFace >= 2.0 * budget + 1e-9 * scale);
}

UpdateList::BlocksById UpdateList::blocksById(LocalParticles const& local) {
    BlocksById byId;
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b)
        byId.emplace_back(blocks[b].block->id.raw(), static_cast<std::uint32_t>(b));
    std::sort(byId.begin(), byId.end());
    return byId;
}

bool UpdateList::findMaster(LocalParticles const& local, BlocksById const& byId,
                            std::uint64_t blockId, Uid uid, std::uint32_t& block,
                            std::uint32_t& index) {
    auto const m = std::lower_bound(byId.begin(), byId.end(), std::pair(blockId, std::uint32_t{0}));
    if (m == byId.end() || m->first != blockId)
        return false;
    ParticleStorage const& ps = local.blocks()[m->second].particles;
    std::size_t const k = ps.find(uid);
    if (k == ParticleStorage::kNotFound || !ps.flags(k).isMaster())
        return false;
    block = m->second;
    index = static_cast<std::uint32_t>(k);
    return true;
}

std::unique_ptr<UpdateList> UpdateList::forConfig(SyncConfig const& config, core::Comm const& comm,
                                                  domain::BlockForest const& forest) {
    if (config.skin == 0.0)
        return nullptr;
    if (!(config.skin > 0.0) || !std::isfinite(config.skin))
        throw core::InputError("sync.skin must be a non-negative finite length");
    if (config.method == SyncMethod::ShadowOwner)
        throw core::InputError("sync.skin applies to NNS-class grains: use sync.method = "
                               "\"nns\" or \"hybrid\", or sync.skin = 0");
    return std::make_unique<UpdateList>(comm, forest.neighbourRanks());
}

UpdateList::UpdateList(core::Comm const& comm, std::vector<int> peers)
    : m_comm(comm.duplicate()) {
    if (m_comm.size() == 1)
        return;
    std::erase(peers, m_comm.rank());
    std::sort(peers.begin(), peers.end());
    peers.erase(std::unique(peers.begin(), peers.end()), peers.end());
    m_exchange = std::make_unique<core::NeighbourExchange>(m_comm, std::move(peers));
    m_from.resize(m_exchange->peers().size());
    m_to.resize(m_exchange->peers().size());
}

int UpdateList::peerSlot(int rank) const {
    if (!m_exchange)
        return -1;
    auto const& peers = m_exchange->peers();
    auto const at = std::lower_bound(peers.begin(), peers.end(), rank);
    return at != peers.end() && *at == rank ? static_cast<int>(at - peers.begin()) : -1;
}

void UpdateList::rebuild(LocalParticles const& local, double budget, core::CommStats& stats) {
    auto const blocks = local.blocks();
    int const rank = m_comm.rank();
    m_valid = false;
    m_budget = budget;
    m_largestMove = 0.0;
    m_followedMove = 0.0;
    m_blocks.resize(blocks.size());
    BlocksById const byId = blocksById(local);
    std::vector<std::vector<Key>> keys(m_from.size());
    for (auto& from : m_from)
        from.clear();
    bool valid = true;
    bool spreads = false;
    for (std::size_t b = 0; b < blocks.size() && valid; ++b) {
        ParticleStorage const& ps = blocks[b].particles;
        BlockState& s = m_blocks[b];
        s.revision = ps.layoutRevision();
        s.reference.assign(ps.positions().begin(), ps.positions().end());
        s.shadows.clear();
        s.nearFaces.clear();
        core::AABB const& box = blocks[b].block->aabb;
        for (std::size_t i = 0; i < ps.size() && valid; ++i) {
            if (ps.flags(i).has(Flag::Spreads)) { // SOS class: Alg. 2 every call
                spreads = true;
                valid = false;
                continue;
            }
            if (!ps.flags(i).isShadow()) {
                if (mayLeave(box, ps.position(i), budget))
                    s.nearFaces.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            BlockRef const owner = ps.owner(i);
            if (owner.rank != rank) { // its owner's send list, in this storage order
                int const p = peerSlot(owner.rank);
                valid = p >= 0;
                if (valid) {
                    m_from[static_cast<std::size_t>(p)].push_back(
                        {static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(i)});
                    keys[static_cast<std::size_t>(p)].push_back({owner.block, ps.uid(i)});
                }
                continue;
            }
            // Its master, on this rank: in storage order, as the reduction without the list
            // visits the shadows, so that the sums are the same.
            Shadow shadow{static_cast<std::uint32_t>(i), 0, 0};
            valid =
                findMaster(local, byId, owner.block, ps.uid(i), shadow.masterBlock, shadow.master);
            if (valid)
                s.shadows.push_back(shadow);
        }
    }
    if (!valid) // the owners get no keys: the list is not used before the next refresh
        for (auto& k : keys)
            k.clear();
    if (m_exchange)
        valid = exchangeKeys(local, byId, keys, stats) && valid;
    m_valid = valid;
    m_idleCalls = spreads ? m_idleLength : 0;
    m_idleLength = spreads ? std::min(2 * m_idleLength, kMaxIdleCalls) : kIdleCalls;
}

bool UpdateList::exchangeKeys(LocalParticles const& local, BlocksById const& byId,
                              std::vector<std::vector<Key>> const& keys, core::CommStats& stats) {
    auto const blocks = local.blocks();
    auto const& peers = m_exchange->peers();
    for (std::size_t p = 0; p < peers.size(); ++p) {
        core::SendBuffer& out = m_exchange->sendBuffer(peers[p]);
        out << std::uint64_t{keys[p].size()};
        for (Key const& k : keys[p])
            out << k.block << k.uid;
    }
    bool found = true;
    m_exchange->start();
    m_exchange->wait([&](int from, core::RecvBuffer& in) {
        std::vector<CopyAt>& to = m_to[static_cast<std::size_t>(peerSlot(from))];
        // The keys come mostly in the order of the last exchange: each is first looked for
        // where the last list went on (the master found there is the one find() finds:
        // (uid, image) is unique), then in the index.
        std::vector<CopyAt> const last = std::exchange(to, {});
        to.reserve(last.size());
        std::size_t next = 0;
        auto const guess = [&](Key const& k, CopyAt& m) {
            for (std::size_t g = next; g < std::min(next + 4, last.size()); ++g) {
                CopyAt const& c = last[g];
                if (c.block >= blocks.size() || blocks[c.block].block->id.raw() != k.block)
                    continue;
                ParticleStorage const& ps = blocks[c.block].particles;
                if (c.index < ps.size() && ps.uid(c.index) == k.uid && isZero(ps.image(c.index)) &&
                    ps.flags(c.index).isMaster()) {
                    m = c;
                    next = g + 1;
                    return true;
                }
            }
            return false;
        };
        std::uint64_t n = 0;
        if (!in.exhausted())
            in >> n;
        for (std::uint64_t q = 0; q < n; ++q) {
            Key k;
            in >> k.block >> k.uid;
            CopyAt m;
            if (guess(k, m) || findMaster(local, byId, k.block, k.uid, m.block, m.index))
                to.push_back(m);
            else
                found = false;
        }
    });
    stats += m_exchange->counters().last();
    // A key skipped above would shift every later position of that peer's list onto another
    // master: a list that did not resolve is emptied, not kept (it is invalid anyway).
    if (!found)
        for (auto& to : m_to)
            to.clear();
    return found;
}

bool UpdateList::holds(LocalParticles const& local) const {
    auto const blocks = local.blocks();
    if (!m_valid || blocks.size() != m_blocks.size())
        return false;
    for (std::size_t b = 0; b < blocks.size(); ++b)
        if (blocks[b].particles.layoutRevision() != m_blocks[b].revision)
            return false;
    return true;
}

UpdateList::Verdict UpdateList::check(LocalParticles const& local, double movedAtMost) {
    if (m_idleCalls > 0) {
        --m_idleCalls;
        return Verdict::Idle;
    }
    if (!holds(local) || !(m_budget > 0.0))
        return Verdict::Refresh;
    auto const blocks = local.blocks();
    m_leavers.resize(blocks.size());
    if (movedAtMost >= 0.0 && std::isfinite(movedAtMost)) {
        // Triangle inequality: the bounds since the refresh add up.
        m_largestMove += movedAtMost;
        if (!(m_largestMove < m_budget * (1.0 - 1e-9)))
            return Verdict::Refresh;
        bool left = false;
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            ParticleStorage const& ps = blocks[b].particles;
            core::AABB const& box = blocks[b].block->aabb;
            m_leavers[b].clear();
            for (std::uint32_t i : m_blocks[b].nearFaces)
                if (!box.contains(ps.position(i)))
                    m_leavers[b].push_back(i);
            left = left || !m_leavers[b].empty();
        }
        return left ? Verdict::Leavers : Verdict::Holds;
    }
    double largest = 0.0;
    bool left = false;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage const& ps = blocks[b].particles;
        core::AABB const& box = blocks[b].block->aabb;
        core::Vec3 const* x = ps.positions().data();
        core::Vec3 const* ref = m_blocks[b].reference.data();
        Flags const* flags = ps.allFlags().data();
        double moved = 0.0;
        bool outside = false;
        bool finite = true;
        // No branch per copy: the maximum and the ORs over every master.
        for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
            bool const master = flags[i].isMaster();
            double const d2 = master ? (x[i] - ref[i]).squaredNorm() : 0.0;
            finite = finite & !std::isnan(d2);
            moved = std::max(moved, d2);
            outside = outside | (master & !box.contains(x[i]));
        }
        if (!finite)
            return Verdict::Refresh;
        largest = std::max(largest, moved);
        m_leavers[b].clear();
        if (outside) {
            left = true;
            for (std::size_t i = 0, n = ps.size(); i < n; ++i)
                if (flags[i].isMaster() && !box.contains(x[i]))
                    m_leavers[b].push_back(static_cast<std::uint32_t>(i));
        }
    }
    m_largestMove = std::sqrt(largest) + m_followedMove;
    // Strictly within the budget, with room for the rounding of the distances the full
    // synchronisation compared (relative 1e-12, far below ParticleSync::kOverlapMargin).
    if (!(m_largestMove < m_budget * (1.0 - 1e-9)))
        return Verdict::Refresh;
    return left ? Verdict::Leavers : Verdict::Holds;
}

UpdateList::Verdict UpdateList::agree(Verdict own) const {
    if (m_comm.size() == 1)
        return own;
    return static_cast<Verdict>(m_comm.allReduce(static_cast<int>(own), core::ReduceOp::Max));
}

bool UpdateList::shareHistories(LocalParticles& local) const {
    if (!m_valid)
        return false;
    auto blocks = local.blocks();
    std::vector<std::array<std::size_t, 2>> shared;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        shared.clear();
        for (Shadow const& s : m_blocks[b].shadows)
            if (s.masterBlock == b)
                shared.push_back({s.index, s.master});
        blocks[b].particles.shareHistories(shared);
    }
    return true;
}

std::size_t UpdateList::update(LocalParticles& local, core::CommStats& stats) {
    auto blocks = local.blocks();
    std::size_t const fields = grainFieldComponents();
    if (m_exchange) { // the remote shadows' messages travel while the local ones are copied
        auto const& peers = m_exchange->peers();
        for (std::size_t p = 0; p < peers.size(); ++p) {
            core::SendBuffer& out = m_exchange->sendBuffer(peers[p]);
            for (CopyAt const& m : m_to[p])
                sync_detail::writeMotion(out, blocks[m.block].particles, m.index, fields);
        }
        m_exchange->start();
    }
    std::size_t updated = 0;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        BlockParticles& target = blocks[b];
        for (Shadow const& s : m_blocks[b].shadows) {
            BlockParticles const& from = blocks[s.masterBlock];
            ParticleStorage const& ps = from.particles;
            sync_detail::copyMotion(ps, s.master, ps.position(s.master), target.particles, s.index);
            if (!target.sent.empty())
                forgetSent(target, ps.uid(s.master));
        }
        updated += m_blocks[b].shadows.size();
    }
    if (m_exchange) {
        std::vector<HistoryEntry> history;
        m_exchange->wait([&](int from, core::RecvBuffer& in) {
            for (CopyAt const& s : m_from[static_cast<std::size_t>(peerSlot(from))]) {
                BlockParticles& target = blocks[s.block];
                sync_detail::readMotion(in, target.particles, s.index, history, fields);
                if (!target.sent.empty())
                    forgetSent(target, target.particles.uid(s.index));
                ++updated;
            }
            if (!in.exhausted())
                throw core::Error("sync: malformed update message from rank " +
                                  std::to_string(from));
        });
        stats += m_exchange->counters().last();
    }
    return updated;
}

bool UpdateList::reduce(LocalParticles& local, std::uint32_t stamp, core::CommStats& stats,
                        bool everywhere) {
    if (!everywhere)
        return false;
    if (!holds(local))
        throw core::Error("sync: the force reduction along the update list was agreed, but a "
                          "storage changed since");
    auto blocks = local.blocks();
    std::vector<HistoryEntry> entries;
    if (m_exchange) { // the remote shadows' shares, by their place in the owner's list
        auto const& peers = m_exchange->peers();
        for (std::size_t p = 0; p < peers.size(); ++p) {
            core::SendBuffer& out = m_exchange->sendBuffer(peers[p]);
            for (std::size_t q = 0; q < m_from[p].size(); ++q) {
                ParticleStorage& ps = blocks[m_from[p][q].block].particles;
                std::size_t const i = m_from[p][q].index;
                if (!sync_detail::mayHaveShare(ps, i))
                    continue;
                sync_detail::touchedEntries(ps, i, stamp, entries);
                if (!sync_detail::hasShare(ps, i, entries))
                    continue;
                out << static_cast<std::uint32_t>(q) << ps.force(i) << ps.torque(i) << entries;
                ps.force(i).setZero();
                ps.torque(i).setZero();
            }
        }
        m_exchange->start();
    }
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage& ps = blocks[b].particles;
        for (Shadow const& s : m_blocks[b].shadows) {
            if (!sync_detail::mayHaveShare(ps, s.index))
                continue;
            if (ps.sharesHistory(s.index)) // its pairs wrote into the master's history
                entries.clear();
            else
                sync_detail::touchedEntries(ps, s.index, stamp, entries);
            sync_detail::addShadowShare(ps, s.index, entries, blocks[s.masterBlock].particles,
                                        s.master);
        }
    }
    if (m_exchange) {
        m_exchange->wait([&](int from, core::RecvBuffer& in) {
            std::vector<CopyAt> const& to = m_to[static_cast<std::size_t>(peerSlot(from))];
            while (!in.exhausted()) {
                std::uint32_t q = 0;
                core::Vec3 force, torque;
                in >> q >> force >> torque >> entries;
                if (q >= to.size())
                    throw core::Error("sync: malformed force message from rank " +
                                      std::to_string(from));
                sync_detail::addShare(blocks[to[q].block].particles, to[q].index, force, torque,
                                      entries);
            }
        });
        stats += m_exchange->counters().last();
    }
    return true;
}

} // namespace regolith::particles
