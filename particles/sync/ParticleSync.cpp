#include "particles/sync/ParticleSync.hpp"

#include "core/Error.hpp"
#include "domain/ForestGeometry.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/sync/CopyScan.hpp"
#include "particles/sync/SpreadRound.hpp"
#include "particles/sync/SyncEngine.hpp"
#include "particles/sync/SyncInbox.hpp"
#include "particles/sync/SyncMessages.hpp"
#include "particles/sync/UpdateList.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <string>

namespace regolith::particles {

using namespace sync_detail;

// ---- Impl: forest view and exchange ---------------------------------------------------------

ParticleSync::Impl::Impl(core::Comm const& comm, domain::BlockForest const& forest,
                         SyncConfig config)
    : m_comm(comm.duplicate())
    , m_forest(&forest) {
    core::Vec3 const extent = forest.domain().extent();
    for (int a = 0; a < 3; ++a)
        m_period[a] = forest.periodic()[static_cast<std::size_t>(a)] ? extent[a] : 0.0;
    m_wrapped = wrappedAxes(forest);
    // Rounding of x + k * period is a few ulps of the coordinates' magnitude; 1e-12 of it is
    // far above that and far below any grain.
    core::AABB const& d = forest.domain();
    m_imageSlack = 1e-12 * std::max(d.min.cwiseAbs().maxCoeff(), d.max.cwiseAbs().maxCoeff());
    if (config.method == SyncMethod::NextNeighbour) {
        std::vector<int> peers = forest.neighbourRanks();
        peers.push_back(comm.rank());
        std::sort(peers.begin(), peers.end());
        m_neighbour = std::make_unique<core::NeighbourExchange>(m_comm, std::move(peers));
    } else {
        m_sparse = std::make_unique<core::SparseExchange>(m_comm);
    }
    for (domain::Block const& b : forest.blocks()) {
        double edge = b.aabb.minEdge();
        std::vector<BlockRef> nbs;
        for (domain::BlockLink const& l : b.neighbours) {
            edge = std::min(edge, l.aabb.minEdge());
            nbs.push_back(BlockRef{l.owner, l.id.raw()});
        }
        std::sort(nbs.begin(), nbs.end());
        nbs.erase(std::unique(nbs.begin(), nbs.end()), nbs.end());
        m_edgeAround[b.id.raw()] = edge;
        DeepTest& t = m_deepTest[b.id.raw()];
        t.reachBox = t.box = b.aabb;
        double const far = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            // No block beyond an open face, and no copy through a wrapped one.
            if (forest.periodic()[static_cast<std::size_t>(a)] &&
                !m_wrapped[static_cast<std::size_t>(a)])
                continue;
            if (b.aabb.min[a] <= d.min[a])
                t.reachBox.min[a] = -far;
            if (b.aabb.max[a] >= d.max[a])
                t.reachBox.max[a] = far;
        }
        t.open = t.reachBox.min != t.box.min || t.reachBox.max != t.box.max;
        auto& groups = m_linksByDirection[b.id.raw()];
        for (std::size_t k = 0; k < b.neighbours.size(); ++k) {
            bool throughWrapped = false;
            for (std::size_t a = 0; a < 3; ++a)
                throughWrapped = throughWrapped || (m_wrapped[a] && b.neighbours[k].image[a] != 0);
            if (throughWrapped)
                continue; // the pairs across a wrapped face are found without copies
            core::AABB const box = b.neighbours[k].imageBox();
            int code = 0;
            for (int a = 0, weight = 1; a < 3; ++a, weight *= 3) {
                int const dir =
                    box.max[a] <= b.aabb.min[a] ? -1 : (box.min[a] >= b.aabb.max[a] ? 1 : 0);
                code += (dir + 1) * weight;
            }
            groups[static_cast<std::size_t>(code)].push_back(static_cast<std::uint32_t>(k));
        }
        m_neighbourBlocks[b.id.raw()] = std::move(nbs);
    }
}

core::SendBuffer& ParticleSync::Impl::out(int rank) {
    return m_neighbour ? m_neighbour->sendBuffer(rank) : m_sparse->sendBuffer(rank);
}

// ---- the public class -----------------------------------------------------------------------

ParticleSync::ParticleSync(core::Comm const& comm, domain::BlockForest const& forest,
                           SyncConfig config)
    : m_comm(&comm)
    , m_impl(std::make_unique<Impl>(comm, forest, config))
    , m_updateList(UpdateList::forConfig(config, comm, forest))
    , m_config(config) {}

void ParticleSync::relocate(domain::BlockForest const& forest) {
    m_impl.reset(); // its communicators are freed before the new ones are made
    m_updateList.reset();
    m_impl = std::make_unique<Impl>(*m_comm, forest, m_config);
    m_updateList = UpdateList::forConfig(m_config, *m_comm, forest);
    m_last = {};
    m_reducedAlongList = false;
}

ParticleSync::~ParticleSync() = default;

void ParticleSync::coverReach(double range) {
    if (!(range >= 0.0) || !std::isfinite(range))
        throw core::Error("ParticleSync::coverReach: the range must be finite and >= 0");
    if (range <= m_config.reach)
        return;
    m_config.reach = range;
    if (m_updateList)
        m_updateList->invalidate(); // its shadows were decided for the narrower balls
}

namespace {

/// Wraps `x` onto the domain along the wrapped axes it lies outside of (domain::wrapOnAxis,
/// the rule of ForestGeometry::wrap); whether it did.
bool wrapsOutside(ParticleSync::Impl const& engine, core::Vec3& x) {
    core::AABB const& d = engine.forest().domain();
    bool moved = false;
    for (int a = 0; a < 3; ++a)
        if (engine.wrapped()[static_cast<std::size_t>(a)] &&
            !(x[a] >= d.min[a] && x[a] < d.max[a])) {
            x[a] = domain::wrapOnAxis(d.min[a], d.max[a], x[a]).second;
            moved = true;
        }
    return moved;
}

/// The Update of shadow `t` (on this rank, same image) from master i of `ps`, applied
/// directly; false if this rank holds no such copy (the buffered path then reports it). A
/// shadow that shares the master's history keeps sharing it (syncInFull) only if the master
/// `stays` in its block and does not spread (Alg. 2 spreads from the shadows' own histories).
bool updateInPlace(LocalParticles& local, ParticleStorage const& ps, std::size_t i,
                   core::Vec3 const& position, CopyRef const& t, BlockRef owner, bool stays) {
    BlockParticles* target = local.find(t.block);
    if (target == nullptr)
        return false;
    std::size_t const k = target->particles.find(ps.uid(i), t.image);
    if (k == ParticleStorage::kNotFound)
        return false;
    copyUpdate(ps, i, position, owner, target->particles, k);
    if ((!stays || ps.flags(i).has(Flag::Spreads)) && target->particles.sharesHistory(k))
        target->particles.history(k).assign(ps.history(i).entries());
    if (!ps.flags(i).has(Flag::Spreads) && !target->sent.empty())
        forgetSent(*target, ps.uid(i));
    return true;
}

/// Masters visited ahead of the one processed: the look-ups of their local shadows start then.
constexpr std::size_t kLookAhead = 8;

/// Starts the index look-ups that updateInPlace will make for master `m` if its holders stay
/// (the steady state): each one is otherwise a cache miss in a table the size of the storage.
void prefetchShadowLookups(ParticleSync::Impl const& engine, LocalParticles const& local,
                           ParticleStorage const& ps, std::size_t m) {
    for (CopyRef const& h : ps.shadowHolders(m))
        if (h.rank == engine.rank())
            if (BlockParticles const* target = local.find(h.block))
                target->particles.prefetchFind(ps.uid(m), h.image);
}

/// Alg. 1 lines 2-24 (NNS class) and Alg. 2 lines 2-13 (SOS class) for master `i` of `bp`,
/// an NNS-class ball grown by `grow` (SyncConfig::skin and half the reach), an SOS-class one
/// by `halfReach`. Returns true if the master leaves this block (transferred or out of the
/// domain).
bool processMaster(ParticleSync::Impl& engine, LocalParticles& local, BlockParticles& bp,
                   ParticleSync::Impl::LinkGroups const& links, std::size_t i, bool nnsClass,
                   bool reachable, double grow, double halfReach, SyncStats& stats) {
    ParticleStorage& ps = bp.particles;
    domain::Block const& block = *bp.block;
    int const me = engine.rank();
    core::Vec3 const& period = engine.period();
    Uid const uid = ps.uid(i);
    core::Vec3 x = ps.position(i);
    // Across a wrapped face the master stays: wrapped in place (ForestGeometry::wrap's rule on
    // those axes), a new copy for the contact detection's lists.
    if (wrapsOutside(engine, x)) {
        ps.moveByPeriods(i, x);
        x = ps.position(i);
    }
    // An NNS-class grain's copies are decided for its ball grown by the skin (UpdateList.hpp).
    double const r = ps.radius(i) + (nnsClass ? grow : halfReach);

    // Ownership (Alg. 1 l. 16-24, Alg. 2 l. 4-12): the block whose box holds the centre.
    bool transfer = false;
    BlockRef newOwner{me, block.id.raw()};
    CopyImage kN = kNoImage; // image of the new owner's copy in the current frame
    HolderList& holders = ps.shadowHolders(i);
    if (!block.aabb.contains(x)) {
        auto const loc = engine.forest().blockContaining(block, x);
        if (!loc && engine.forest().insideDomain(x))
            throw core::Error("sync: particle uid " + std::to_string(uid) +
                              " moved farther than the neighbour blocks of its block in one "
                              "step; reduce time.dt");
        if (!loc) { // left an open domain: remove the grain and all its shadows
            for (CopyRef const& h : holders) {
                writeHeader(engine.out(h.rank), RecordKind::Remove, h.block);
                engine.out(h.rank) << uid << h.image;
            }
            ++stats.leftDomain;
            stats.departed.emplace_back(uid, x);
            return true;
        }
        kN = imageThroughLink(kNoImage, loc->image);
        transfer = !(loc->id == block.id && isZero(kN));
        newOwner = BlockRef{loc->owner, loc->id.raw()};
    }

    // An SOS-class grain whose ball the block's neighbourhood holds, and that stays in its
    // block, has its master spread here rather than in round 2: the same copy test on the
    // same position finds the same blocks (Alg. 2 l. 15-28 for the master), and its shadows
    // then only test in round 2 whether they still overlap theirs. The class travels with
    // every record below; after a transfer the new block's neighbourhood may not hold the
    // ball, and its copies spread in full for this call.
    bool const spreadsHere = !nnsClass && reachable && !transfer;
    Flags const flags =
        Flags(ps.flags(i)).set(Flag::Spreads, !nnsClass).set(Flag::MasterReachesAll, spreadsHere);
    if (flags != ps.flags(i))
        ps.setFlags(i, flags);

    // Where copies go, in the current frame.
    std::vector<CopyRef>& targets = engine.scratch(0); // reused: no allocation per grain
    targets.clear();
    if (nnsClass || spreadsHere) {
        engine.forEachReachableLink(block, links, x, r, [&](domain::BlockLink const& l) {
            if (!engine.mayReach(l, x, r))
                return;
            CopyImage const k = imageThroughLink(kNoImage, l.image);
            if (copyNeeded(l.aabb, x, k, r, period))
                targets.push_back(CopyRef{l.owner, l.id.raw(), k});
        });
    }
    if (!nnsClass) // SOS: every holder is updated; a shadow that left its block drops itself
        targets.insert(targets.end(), holders.begin(), holders.end());
    if (transfer && (!nnsClass || copyNeeded(block.aabb, x, kNoImage, r, period)))
        targets.push_back(CopyRef{me, block.id.raw(), kNoImage}); // the old master's block
    std::sort(targets.begin(), targets.end());
    targets.erase(std::unique(targets.begin(), targets.end()), targets.end());

    // The frame after a transfer across a periodic boundary moves every image by -kN.
    CopyRef const ownerCopy{newOwner.rank, newOwner.block, kN};
    // Wrapped like blockContaining decides (clamped: x + kN * period may round onto the
    // upper domain face when x crossed the lower one by less than an ulp).
    core::Vec3 const newPosition = transfer && !isZero(kN) ? engine.forest().wrap(x) : x;
    // Without a transfer the frame stays (kN = 0) and the new holders are the targets.
    std::vector<CopyRef>& newHolders = transfer ? engine.scratch(1) : targets;
    if (transfer) {
        newHolders.clear();
        for (CopyRef const& t : targets)
            if (!(t == ownerCopy))
                newHolders.push_back(CopyRef{t.rank, t.block, subtractImages(t.image, kN)});
        std::sort(newHolders.begin(), newHolders.end());
    }

    for (CopyRef const& t : targets) {
        if (transfer && t == ownerCopy)
            continue;
        CopyImage const k = subtractImages(t.image, kN);
        if (std::binary_search(holders.begin(), holders.end(), t)) {
            // A shadow on this rank that keeps its key: written in place, not serialised.
            // Safe before the receive round: no record of this round removes or moves it (its
            // master sends it this update only), and it changes no index.
            if (t.rank == me && sameImage(t.image, k) &&
                updateInPlace(local, ps, i, newPosition, t, newOwner, !transfer)) {
                ++stats.updated;
                continue;
            }
            core::SendBuffer& b = engine.out(t.rank);
            writeHeader(b, RecordKind::Update, t.block);
            writeUpdate(b, ps, i, newPosition, t.image, k, newOwner);
        } else {
            core::SendBuffer& b = engine.out(t.rank);
            writeHeader(b, RecordKind::Copy, t.block);
            writeFull(b, ps, i, newPosition, k, newOwner, {});
        }
    }
    if (nnsClass) {
        for (CopyRef const& h : holders) {
            if (!std::binary_search(targets.begin(), targets.end(), h)) {
                writeHeader(engine.out(h.rank), RecordKind::Remove, h.block);
                engine.out(h.rank) << uid << h.image;
            }
        }
    }
    if (transfer) {
        core::SendBuffer& b = engine.out(newOwner.rank);
        writeHeader(b, RecordKind::Promote, newOwner.block);
        b << kN;
        writeFull(b, ps, i, newPosition, kNoImage, newOwner, newHolders);
        return true;
    }
    if (!std::equal(holders.begin(), holders.end(), newHolders.begin(), newHolders.end()))
        holders.assign(newHolders.begin(), newHolders.end());
    return false;
}

/// Whether the ball (x, r) of a master of `block` lies inside the block grown by `edge` (the
/// smallest edge around it), i.e. inside the block and its neighbours: the condition under
/// which the master alone can reach every block its grain overlaps (NNS). After a step the
/// centre may have left the block, so this is stricter than r < edge. Beyond an open domain
/// face there is nothing to reach.
bool withinNeighbourhood(ParticleSync::Impl const& engine, domain::Block const& block, double edge,
                         core::Vec3 const& x, double r) {
    core::AABB const& domain = engine.forest().domain();
    auto const& periodic = engine.forest().periodic();
    double const reach = r * (1.0 + ParticleSync::kOverlapMargin);
    for (int a = 0; a < 3; ++a) {
        bool const open =
            !periodic[static_cast<std::size_t>(a)] || engine.wrapped()[static_cast<std::size_t>(a)];
        bool const lowOk =
            (open && block.aabb.min[a] <= domain.min[a]) || x[a] - reach > block.aabb.min[a] - edge;
        bool const highOk =
            (open && block.aabb.max[a] >= domain.max[a]) || x[a] + reach < block.aabb.max[a] + edge;
        if (!lowOk || !highOk)
            return false;
    }
    return true;
}

} // namespace

void ParticleSync::syncInFull(LocalParticles& local,
                              std::span<std::vector<std::uint32_t> const> only, double grow) {
    Impl& engine = *m_impl;
    m_last = SyncStats{};
    // Every ball reaches half the interaction range farther (SyncConfig::reach).
    double const halfReach = 0.5 * m_config.reach;
    bool const skinned = grow > 0.0;
    grow += halfReach;
    bool const twoRounds = m_config.method != SyncMethod::NextNeighbour;
    // Whether this rank has copies round 2 (spread) may act on: SOS-class shadows, and
    // SOS-class masters processed below. Shadows and promotions that round 1 brings come from
    // SOS-class masters, whose senders say so; if no rank does, round 2 has nothing to do
    // anywhere and every rank skips it (hybrid with only NNS-class grains: one exchange per
    // call, as NNS).
    bool spreadWork = false;
    bool const spreads = m_config.method == SyncMethod::ShadowOwner;
    for (BlockParticles& bp : local.blocks()) {
        ParticleStorage& ps = bp.particles;
        double const edge = engine.edgeAround(bp.block->id.raw());
        auto const& deep = engine.deepTest(bp.block->id.raw());
        auto const& links = engine.linksByDirection(bp.block->id.raw());
        std::vector<Uid> leaving;
        bp.spreadingMasters.clear();
        // The common case, a small grain deep inside its block with no shadows to update or
        // remove, needs nothing sent (Alg. 1/2 would find no target): the scan leaves it out.
        std::span<std::uint32_t const> visit;
        if (only.empty()) {
            MasterScan const scan = scanMasters(engine, bp, spreads, grow, engine.scratchMasters());
            spreadWork = spreadWork || scan.spreadingShadows;
            visit = scan.visit;
        } else { // the update list's leavers (no SOS-class copy exists then)
            visit = only[static_cast<std::size_t>(&bp - local.blocks().data())];
        }
        for (std::size_t n = 0; n < visit.size(); ++n) {
            // Two stages: the holder list's block first, read by the index look-ups after.
            if (n + 2 * kLookAhead < visit.size())
                ps.shadowHolders(visit[n + 2 * kLookAhead]).prefetch();
            if (n + kLookAhead < visit.size())
                prefetchShadowLookups(engine, local, ps, visit[n + kLookAhead]);
            std::size_t const i = visit[n];
            // Else taken for a grain that left an open domain, and dropped, even if periodic.
            if (!ps.position(i).allFinite())
                throw core::Error("sync: particle uid " + std::to_string(ps.uid(i)) +
                                  " has a non-finite position; the step is unstable: reduce "
                                  "time.dt or the contact stiffness");
            double const r = ps.radius(i) + grow;
            bool const small = r < edge;
            if (small && ps.shadowHolders(i).empty() &&
                engine.deepInside(deep, ps.position(i), r)) {
                ps.setFlags(i, Flags(ps.flags(i)).set(Flag::Spreads, spreads));
                continue;
            }
            bool const reachable =
                small && withinNeighbourhood(engine, *bp.block, edge, ps.position(i), r);
            if (m_config.method == SyncMethod::NextNeighbour && !reachable) {
                std::ostringstream msg;
                msg << "NNS cannot synchronise particle uid " << ps.uid(i) << ": its radius "
                    << ps.radius(i) << (skinned ? " plus sync.skin" : "")
                    << (halfReach > 0.0 ? " plus half the contact model's range" : "")
                    << (small ? " plus its displacement in one step reach" : " is not below")
                    << " the smallest "
                    << (engine.forest().subdomains() == domain::Subdomains::RankBoxes ? "subdomain"
                                                                                      : "block")
                    << " edge " << edge << " it may touch; set sync.method = \"sos\" or \"hybrid\""
                    << (skinned ? ", reduce sync.skin" : "")
                    << (small ? ", or reduce time.dt" : "");
                // Found here alone, mid-sync: the job ends with this message (exit 2).
                throw core::RankInputError(msg.str());
            }
            bool const nnsClass = m_config.method == SyncMethod::NextNeighbour ||
                                  (m_config.method == SyncMethod::Hybrid && reachable);
            spreadWork = spreadWork || !nnsClass;
            if (processMaster(engine, local, bp, links, i, nnsClass, reachable, grow, halfReach,
                              m_last))
                leaving.push_back(ps.uid(i));
            else if (twoRounds && !nnsClass && !ps.flags(i).has(Flag::MasterReachesAll) &&
                     !engine.deepInside(deep, ps.position(i), r))
                bp.spreadingMasters.push_back({ps.uid(i), i}); // spread visits it (round 2)
        }
        // The storage's layout changes from here on, and its shadows stop sharing their
        // masters' histories (UpdateList::shareHistories). Those the masters above updated in
        // place kept the history shared, not a copy, as along the update list: the list shares
        // them again after the call, or gives them their masters' histories (syncOn).
        ps.forgetSharedHistories();
        for (Uid uid : leaving)
            ps.removeUid(uid);
    }
    receiveRound(engine, local, m_last, spreadWork);
    if (twoRounds && engine.flagRaised()) {
        for (BlockParticles& bp : local.blocks())
            spread(engine, bp, halfReach, m_last);
        receiveRound(engine, local, m_last);
    }
    m_counters.record(m_last.comm);
}

int ParticleSync::syncUntilConverged(LocalParticles& local, int maxCalls) {
    for (int calls = 1; calls <= maxCalls; ++calls) {
        sync(local);
        if (m_impl->comm().allReduce(m_last.created, core::ReduceOp::Sum) == 0)
            return calls;
    }
    throw core::Error("shadow synchronisation did not converge in " + std::to_string(maxCalls) +
                      " calls");
}

} // namespace regolith::particles
