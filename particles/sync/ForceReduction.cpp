// ParticleSync::reduceForces: shadow -> master reduction of forces, torques and contact
// history ("reduce forces/torques shadow->master" of the time step in docs/design.md).
#include "core/Error.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/sync/CopyScan.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/SyncMessages.hpp"
#include "particles/sync/UpdateList.hpp"

#include <algorithm>
#include <string>
#include <tuple>

namespace regolith::particles {

using namespace sync_detail;

namespace {

/// One contribution to a master's force in reproducible mode.
struct Contribution {
    std::size_t block = 0; ///< index into local.blocks()
    std::size_t master = 0;
    Uid partner = kInvalidUid;
    core::Vec3 force = core::Vec3::Zero();
    core::Vec3 torque = core::Vec3::Zero();
};

std::size_t masterIndex(LocalParticles& local, std::uint64_t block, Uid uid, std::size_t& b) {
    auto const blocks = local.blocks();
    for (b = 0; b < blocks.size(); ++b)
        if (blocks[b].block->id.raw() == block)
            break;
    std::size_t const i =
        b < blocks.size() ? blocks[b].particles.find(uid) : ParticleStorage::kNotFound;
    if (i == ParticleStorage::kNotFound || !blocks[b].particles.flags(i).isMaster())
        throw core::Error("sync: force for uid " + std::to_string(uid) + " sent to block " +
                          std::to_string(block) + ", which does not hold its master");
    return i;
}

/// How many copies ahead the loops below start loading what they will need.
constexpr std::size_t kAhead = 8;

/// Starts the look-up of copy s's master if s is a shadow whose master is on this rank: the
/// in-place reduction below finds it some shadows later, and the look-up is otherwise a cache
/// miss in a table the size of the storage.
void prefetchLocalMaster(ParticleSync::Impl const& engine, LocalParticles const& local,
                         ParticleStorage const& ps, std::size_t s) {
    if (s >= ps.size() || !ps.flags(s).isShadow())
        return;
    BlockRef const owner = ps.owner(s);
    if (owner.rank != engine.rank())
        return;
    if (BlockParticles const* master = local.find(owner.block))
        master->particles.prefetchFind(ps.uid(s));
}

/// Every ParticleSync::kHistoryPruneInterval passes, drops the masters' history entries not
/// stamped `stamp`. Each history sits at its own heap address, so a few are fetched ahead.
void pruneMasterHistories(LocalParticles& local, std::uint32_t stamp) {
    if (stamp % ParticleSync::kHistoryPruneInterval != 0)
        return;
    for (BlockParticles& bp : local.blocks()) {
        ParticleStorage& ps = bp.particles;
        for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
            if (i + kAhead < n)
                ps.history(i + kAhead).prefetch();
            if (ps.flags(i).isMaster())
                ps.history(i).keepOnly(stamp);
        }
    }
}

/// Sends each shadow's history entries of this pass (and, unless `records`, its force and
/// torque) to its master; applies what arrives. Returns the reproducible contributions.
std::vector<Contribution> exchangeShadowShares(ParticleSync::Impl& engine, LocalParticles& local,
                                               std::vector<std::vector<ForceRecord>>* records,
                                               std::uint32_t stamp, core::CommStats& stats) {
    auto blocks = local.blocks();
    std::vector<Contribution> contributions;
    std::vector<HistoryEntry> hist;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage& ps = blocks[b].particles;
        constexpr std::uint8_t kShadow = Flags(Flag::Shadow).bits();
        forEachWithFlags<kShadow>(ps.allFlags(), [&](std::size_t i) {
            if (records == nullptr)
                prefetchLocalMaster(engine, local, ps, i + kAhead);
            touchedEntries(ps, i, stamp, hist);
            // Reproducible mode sends the forces as records: only the history here.
            if (records != nullptr ? hist.empty() : !hasShare(ps, i, hist))
                return;
            BlockRef const owner = ps.owner(i);
            if (owner.rank == engine.rank() && records == nullptr) {
                // The master is on this rank: added in place, not serialised. (Reproducible
                // mode sends no forces here, only history, and keeps one path for it.)
                std::size_t ob = 0;
                std::size_t const m = masterIndex(local, owner.block, ps.uid(i), ob);
                addShadowShare(ps, i, hist, blocks[ob].particles, m);
                return;
            }
            core::SendBuffer& out = engine.out(owner.rank);
            writeHeader(out, RecordKind::Force, owner.block);
            out << ps.uid(i) << ps.force(i) << ps.torque(i) << hist;
            ps.force(i).setZero();
            ps.torque(i).setZero();
        });
        if (records == nullptr)
            continue;
        for (ForceRecord const& r : (*records)[b]) {
            if (ps.flags(r.copy).isMaster()) {
                contributions.push_back(Contribution{b, r.copy, r.partner, r.force, r.torque});
                continue;
            }
            BlockRef const owner = ps.owner(r.copy);
            core::SendBuffer& out = engine.out(owner.rank);
            writeHeader(out, RecordKind::ForceRecords, owner.block);
            out << ps.uid(r.copy) << r.partner << r.force << r.torque;
        }
    }
    engine.exchange(stats, [&](int from, core::RecvBuffer& in) {
        while (!in.exhausted()) {
            RecordKind kind{};
            std::uint64_t block = 0;
            Uid uid = kInvalidUid;
            in >> kind >> block >> uid;
            std::size_t b = 0;
            std::size_t const i = masterIndex(local, block, uid, b);
            ParticleStorage& ps = blocks[b].particles;
            if (kind == RecordKind::Force) {
                core::Vec3 f, t;
                std::vector<HistoryEntry> entries;
                in >> f >> t >> entries;
                addShare(ps, i, f, t, entries);
            } else if (kind == RecordKind::ForceRecords) {
                Contribution c{b, i, kInvalidUid, {}, {}};
                in >> c.partner >> c.force >> c.torque;
                contributions.push_back(c);
            } else {
                throw core::Error("sync: malformed force message from rank " +
                                  std::to_string(from));
            }
        }
    });
    pruneMasterHistories(local, stamp);
    return contributions;
}

} // namespace

bool ParticleSync::listHoldsHere(LocalParticles const& local) const {
    return m_updateList && m_updateList->holds(local);
}

void ParticleSync::reduceForces(LocalParticles& local, std::uint32_t stamp) {
    // Along the update list if it holds on every rank (no storage changed since the last sync
    // anywhere): the same shares, without looking the masters up.
    bool const here = listHoldsHere(local);
    reduceForces(local, stamp, m_updateList && m_comm->size() > 1 ? m_comm->allTrue(here) : here);
}

void ParticleSync::reduceForces(LocalParticles& local, std::uint32_t stamp, bool listEverywhere) {
    core::CommStats stats;
    m_reducedAlongList = m_updateList && m_updateList->reduce(local, stamp, stats, listEverywhere);
    if (m_reducedAlongList)
        pruneMasterHistories(local, stamp);
    else
        exchangeShadowShares(*m_impl, local, nullptr, stamp, stats);
    m_counters.record(stats);
}

void ParticleSync::reduceForces(LocalParticles& local,
                                std::vector<std::vector<ForceRecord>>& records,
                                std::uint32_t stamp) {
    if (records.size() != local.blocks().size())
        throw core::Error("reduceForces: one record list per local block expected");
    core::CommStats stats;
    auto contributions = exchangeShadowShares(*m_impl, local, &records, stamp, stats);
    // Every master's force summed from zero in ascending partner uid: the same sum whatever
    // block evaluated each contact (docs/design.md, "Reproducible mode").
    std::sort(contributions.begin(), contributions.end(),
              [](Contribution const& a, Contribution const& b) {
                  if (std::tie(a.block, a.master) != std::tie(b.block, b.master))
                      return std::tie(a.block, a.master) < std::tie(b.block, b.master);
                  return partnerOrder(a, b);
              });
    auto blocks = local.blocks();
    for (BlockParticles& bp : blocks)
        bp.particles.forEachMaster([&](std::size_t i) {
            bp.particles.force(i).setZero();
            bp.particles.torque(i).setZero();
        });
    for (Contribution const& c : contributions) {
        ParticleStorage& ps = blocks[c.block].particles;
        ps.force(c.master) += c.force;
        ps.torque(c.master) += c.torque;
    }
    for (auto& r : records)
        r.clear();
    m_counters.record(stats);
}

} // namespace regolith::particles
