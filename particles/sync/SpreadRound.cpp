#include "particles/sync/SpreadRound.hpp"

#include "particles/sync/CopyScan.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/SyncInbox.hpp"
#include "particles/sync/SyncMessages.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace regolith::particles::sync_detail {

namespace {

/// The indices, ascending, of the copies of `bp` that spread may have to act on: every
/// SOS-class shadow, and the SOS-class masters of `bp.spreadingMasters` (the others are deep
/// inside their block, where spread would skip them). One pass over the flag bytes instead of
/// a position test per master. The order is that of a full pass, so the records are too.
std::vector<std::size_t> const& spreadingCopies(ParticleSync::Impl& engine, BlockParticles& bp) {
    ParticleStorage const& ps = bp.particles;
    std::vector<std::size_t>& order = engine.scratchIndices();
    order.clear();
    for (BlockParticles::MasterHint const& m : bp.spreadingMasters) {
        // Round 1 moves few copies (a removal moves the last one into its slot), so the
        // index noted then is nearly always still right; a hash look-up is the fallback.
        bool const still =
            m.index < ps.size() && ps.uid(m.index) == m.uid && ps.flags(m.index).isMaster();
        std::size_t const i = still ? m.index : ps.find(m.uid);
        if (i != ParticleStorage::kNotFound && ps.flags(i).isMaster() &&
            ps.flags(i).has(Flag::Spreads))
            order.push_back(i);
    }
    bp.spreadingMasters.clear();
    // Two ascending runs (round 1 noted the masters in index order; a removal can break
    // that) merged in place: no O(n log n) sort per call.
    auto const masters = static_cast<std::ptrdiff_t>(order.size());
    if (!std::is_sorted(order.begin(), order.end()))
        std::sort(order.begin(), order.end());
    constexpr std::uint8_t kSpreadingShadow = Flags(Flag::Shadow | Flag::Spreads).bits();
    forEachWithFlags<kSpreadingShadow>(ps.allFlags(), [&](std::size_t i) { order.push_back(i); });
    std::inplace_merge(order.begin(), order.begin() + masters, order.end());
    order.erase(std::unique(order.begin(), order.end()), order.end());
    return order;
}

} // namespace

/// Alg. 2 lines 15-28 for every SOS-class copy of `bp`: create missing shadows on the
/// neighbour blocks (one layer per call), drop shadows that no longer touch the block.
void spread(ParticleSync::Impl& engine, BlockParticles& bp, double halfReach, SyncStats& stats) {
    ParticleStorage& ps = bp.particles;
    domain::Block const& block = *bp.block;
    int const me = engine.rank();
    std::uint64_t const self = block.id.raw();
    core::Vec3 const& period = engine.period();
    auto const& links = engine.linksByDirection(self);
    std::vector<CopyKey> drop;
    for (std::size_t const i : spreadingCopies(engine, bp)) {
        Uid const uid = ps.uid(i);
        CopyImage const k = ps.image(i);
        core::Vec3 const& x = ps.position(i);
        double const r = ps.radius(i) + halfReach;
        BlockRef const owner = ps.owner(i);
        bool const master = ps.flags(i).isMaster();
        if (!master && !copyNeeded(block.aabb, x, k, r, period)) {
            drop.push_back(ps.key(i));
            core::SendBuffer& b = engine.out(owner.rank);
            writeHeader(b, RecordKind::HolderRemoved, owner.block);
            b << uid << CopyRef{me, self, k};
            for (BlockRef const& nb : engine.neighbourBlocks(self)) {
                writeHeader(engine.out(nb.rank), RecordKind::ForgetSent, nb.block);
                engine.out(nb.rank) << SentEntry{self, uid, k};
            }
            continue;
        }
        // The master ordered a copy on every block the ball overlaps in round 1: nothing left
        // for this shadow to order (Flag::MasterReachesAll).
        if (!master && ps.flags(i).has(Flag::MasterReachesAll))
            continue;
        core::Vec3 const local = localPosition(x, k, period);
        engine.forEachReachableLink(block, links, local, r, [&](domain::BlockLink const& l) {
            // The master itself first (image k - l.image = 0): a shadow's ball always reaches
            // back into its master's block, so this link is the commonest; no geometry.
            if (l.id.raw() == owner.block && k[0] == l.image[0] && k[1] == l.image[1] &&
                k[2] == l.image[2])
                return;
            if (!engine.mayReach(l, local, r))
                return;
            CopyImage const kt = imageThroughLink(k, l.image);
            if (!copyNeeded(l.aabb, x, kt, r, period))
                return;
            CopyRef const t{l.owner, l.id.raw(), kt};
            if (master) {
                auto& h = ps.shadowHolders(i);
                auto const at = std::lower_bound(h.begin(), h.end(), t);
                if (at != h.end() && *at == t)
                    return;
                h.insert(at, t);
            } else {
                if (!bp.sent.insert(SentEntry{l.id.raw(), uid, kt}))
                    return;
                core::SendBuffer& b = engine.out(owner.rank);
                writeHeader(b, RecordKind::HolderAdded, owner.block);
                b << uid << t;
            }
            core::SendBuffer& b = engine.out(l.owner);
            writeHeader(b, RecordKind::Copy, l.id.raw());
            writeFull(b, ps, i, x, kt, owner, {});
        });
    }
    for (CopyKey const& key : drop) {
        ps.removeUid(key.uid, key.image);
        forgetSent(bp, key.uid);
        ++stats.removed;
    }
}

} // namespace regolith::particles::sync_detail
