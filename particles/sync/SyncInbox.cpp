#include "particles/sync/SyncInbox.hpp"

#include "core/Error.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/SyncMessages.hpp"

#include <algorithm>
#include <map>
#include <string>

namespace regolith::particles::sync_detail {

namespace {

struct Promotion {
    CopyImage oldImage = kNoImage;
    FullState state;
};

/// Everything one block received in a round.
struct Inbox {
    std::vector<CopyKey> removes;
    std::vector<UpdateState> updates;
    std::vector<Promotion> promotions;
    std::vector<FullState> copies;
    std::vector<std::pair<Uid, CopyRef>> holdersAdded;
    std::vector<std::pair<Uid, CopyRef>> holdersRemoved;
    std::vector<SentEntry> forget;
};

std::string describe(Uid uid, CopyImage const& k, std::uint64_t block) {
    return "uid " + std::to_string(uid) + " image (" + std::to_string(k[0]) + "," +
           std::to_string(k[1]) + "," + std::to_string(k[2]) + ") in block " +
           std::to_string(block);
}

void parse(core::RecvBuffer& in, int from, std::map<std::uint64_t, Inbox>& boxes,
           LocalParticles const& local) {
    while (!in.exhausted()) {
        RecordKind kind{};
        std::uint64_t block = 0;
        in >> kind >> block;
        if (local.find(block) == nullptr)
            throw core::Error("sync: rank " + std::to_string(from) + " sent a record for block " +
                              std::to_string(block) + ", which this rank does not own");
        Inbox& box = boxes[block];
        switch (kind) {
        case RecordKind::Copy:
            box.copies.push_back(readFull(in));
            break;
        case RecordKind::Update:
            box.updates.push_back(readUpdate(in));
            break;
        case RecordKind::Promote: {
            Promotion p;
            in >> p.oldImage;
            p.state = readFull(in);
            box.promotions.push_back(std::move(p));
            break;
        }
        case RecordKind::Remove: {
            CopyKey k;
            in >> k.uid >> k.image;
            box.removes.push_back(k);
            break;
        }
        case RecordKind::HolderAdded:
        case RecordKind::HolderRemoved: {
            std::pair<Uid, CopyRef> h;
            in >> h.first >> h.second;
            (kind == RecordKind::HolderAdded ? box.holdersAdded : box.holdersRemoved).push_back(h);
            break;
        }
        case RecordKind::ForgetSent: {
            SentEntry e;
            in >> e;
            box.forget.push_back(e);
            break;
        }
        default:
            throw core::Error("sync: malformed message from rank " + std::to_string(from) +
                              ": unknown record kind " + std::to_string(static_cast<int>(kind)));
        }
    }
}

void apply(BlockParticles& bp, Inbox& box, SyncStats& stats) {
    ParticleStorage& ps = bp.particles;
    std::uint64_t const self = bp.block->id.raw();
    for (CopyKey const& k : box.removes) {
        std::size_t const i = ps.find(k.uid, k.image);
        if (i == ParticleStorage::kNotFound)
            continue; // already dropped by this block in the same round (SOS)
        if (ps.flags(i).isMaster())
            throw core::Error("sync: remove order for the master " +
                              describe(k.uid, k.image, self));
        ps.remove(i);
        forgetSent(bp, k.uid);
        ++stats.removed;
    }
    // Updates that re-key: take those copies out first so that old and new keys never clash.
    std::vector<std::pair<FullState, UpdateState const*>> rekeyed;
    for (UpdateState const& u : box.updates) {
        if (sameImage(u.oldImage, u.newImage))
            continue;
        std::size_t const i = ps.find(u.uid, u.oldImage);
        if (i == ParticleStorage::kNotFound)
            throw core::Error("sync: update for " + describe(u.uid, u.oldImage, self) +
                              ", which this block does not hold");
        FullState s;
        static_cast<GrainRow&>(s.init) = ps.row(i);
        s.init.owner = ps.owner(i);
        s.init.image = u.newImage;
        s.init.fields = ps.fieldValues(i);
        ps.remove(i);
        rekeyed.emplace_back(std::move(s), &u);
    }
    for (Promotion const& p : box.promotions) {
        Uid const uid = p.state.init.uid;
        if (std::size_t const i = ps.find(uid, p.oldImage); i != ParticleStorage::kNotFound)
            ps.remove(i);
    }
    std::map<Uid, CopyImage> frameShifts; // per grain: its images all move by -delta
    for (auto& [s, u] : rekeyed) {
        std::size_t const i = addFull(ps, s, false);
        applyUpdate(ps, i, *u);
        frameShifts[u->uid] = subtractImages(u->oldImage, u->newImage);
        ++stats.updated;
    }
    for (UpdateState const& u : box.updates) {
        if (!sameImage(u.oldImage, u.newImage))
            continue;
        std::size_t const i = ps.find(u.uid, u.oldImage);
        if (i == ParticleStorage::kNotFound)
            throw core::Error("sync: update for " + describe(u.uid, u.oldImage, self) +
                              ", which this block does not hold");
        applyUpdate(ps, i, u);
        if (!u.flags.has(Flag::Spreads))
            forgetSent(bp, u.uid);
        ++stats.updated;
    }
    for (Promotion const& p : box.promotions) {
        std::size_t const i = addFull(ps, p.state, true);
        if (p.state.init.flags.has(Flag::Spreads))
            bp.spreadingMasters.push_back({p.state.init.uid, i}); // spreads in round 2 (Alg. 2)
        if (!isZero(p.oldImage))
            frameShifts[p.state.init.uid] = p.oldImage;
        ++stats.transferred;
    }
    for (auto const& [uid, delta] : frameShifts)
        bp.sent.shift(uid, delta);
    for (FullState const& s : box.copies) {
        if (ps.contains(s.init.uid, s.init.image)) {
            ++stats.duplicates;
            continue;
        }
        addFull(ps, s, false);
        ++stats.created;
    }
    for (auto const& [uid, holder] : box.holdersAdded) {
        std::size_t const i = ps.find(uid);
        if (i == ParticleStorage::kNotFound || !ps.flags(i).isMaster())
            throw core::Error("sync: new shadow of uid " + std::to_string(uid) +
                              " reported to block " + std::to_string(self) +
                              ", which does not hold its master");
        auto& h = ps.shadowHolders(i);
        auto const at = std::lower_bound(h.begin(), h.end(), holder);
        if (at == h.end() || !(*at == holder))
            h.insert(at, holder);
    }
    for (auto const& [uid, holder] : box.holdersRemoved) {
        std::size_t const i = ps.find(uid);
        if (i == ParticleStorage::kNotFound || !ps.flags(i).isMaster())
            continue; // the master left the domain in this round
        auto& h = ps.shadowHolders(i);
        h.erase(std::remove(h.begin(), h.end(), holder), h.end());
    }
    for (SentEntry const& e : box.forget)
        bp.sent.erase(e);
}

} // namespace

void forgetSent(BlockParticles& bp, Uid uid) {
    bp.sent.forget(uid);
}

void receiveRound(ParticleSync::Impl& engine, LocalParticles& local, SyncStats& stats,
                  bool raiseFlag) {
    std::map<std::uint64_t, Inbox> boxes;
    engine.exchange(
        stats.comm, [&](int from, core::RecvBuffer& in) { parse(in, from, boxes, local); },
        raiseFlag);
    for (auto& [block, box] : boxes)
        apply(*local.find(block), box, stats);
}

} // namespace regolith::particles::sync_detail
