#include "particles/sync/UpdateList.hpp"

#include "core/Error.hpp"
#include "particles/sync/SyncInbox.hpp"
#include "particles/sync/SyncMessages.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace regolith::particles {

namespace {

/// Whether a master at `x` may leave `box` by moving less than `budget`: within twice the
/// budget of a face (the factor and the relative 1e-9 of the coordinates cover the rounding of
/// the distances; a master outside already, or not finite, counts too).
bool mayLeave(core::AABB const& box, core::Vec3 const& x, double budget) {
    double const toFace = std::min((x - box.min).minCoeff(), (box.max - x).minCoeff());
    double const scale = x.cwiseAbs().maxCoeff() + box.max.cwiseAbs().maxCoeff();
    return !(toFace >= 2.0 * budget + 1e-9 * scale);
}

} // namespace

std::unique_ptr<UpdateList> UpdateList::forConfig(SyncConfig const& config, int ranks) {
    if (config.skin == 0.0)
        return nullptr;
    if (!(config.skin > 0.0) || !std::isfinite(config.skin))
        throw core::InputError("sync.skin must be a non-negative finite length");
    if (config.method == SyncMethod::ShadowOwner)
        throw core::InputError("sync.skin applies to NNS-class grains: use sync.method = "
                               "\"nns\" or \"hybrid\", or sync.skin = 0");
    if (ranks != 1)
        throw core::InputError("sync.skin needs one rank (every shadow's master in the process); "
                               "this run has " +
                               std::to_string(ranks) + ": set sync.skin = 0");
    return std::make_unique<UpdateList>();
}

void UpdateList::rebuild(LocalParticles const& local, int rank, double budget) {
    auto const blocks = local.blocks();
    m_valid = false;
    m_rank = rank;
    m_budget = budget;
    m_largestMove = 0.0;
    m_blocks.resize(blocks.size());
    std::vector<std::pair<std::uint64_t, std::uint32_t>> byId; // block id -> local index
    for (std::size_t b = 0; b < blocks.size(); ++b)
        byId.emplace_back(blocks[b].block->id.raw(), static_cast<std::uint32_t>(b));
    std::sort(byId.begin(), byId.end());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage const& ps = blocks[b].particles;
        BlockState& s = m_blocks[b];
        s.revision = ps.layoutRevision();
        s.reference.assign(ps.positions().begin(), ps.positions().end());
        s.shadows.clear();
        s.nearFaces.clear();
        core::AABB const& box = blocks[b].block->aabb;
        for (std::size_t i = 0; i < ps.size(); ++i) {
            if (ps.flags(i).has(Flag::Spreads))
                return; // SOS class: Alg. 2 every call
            if (!ps.flags(i).isShadow()) {
                if (mayLeave(box, ps.position(i), budget))
                    s.nearFaces.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            // Its master, on this rank (else Alg. 1 every call): in storage order, as the
            // reduction without the list visits the shadows, so that the sums are the same.
            BlockRef const owner = ps.owner(i);
            auto const m = std::lower_bound(byId.begin(), byId.end(),
                                            std::pair(owner.block, std::uint32_t{0}));
            if (owner.rank != rank || m == byId.end() || m->first != owner.block)
                return;
            ParticleStorage const& masters = blocks[m->second].particles;
            std::size_t const k = masters.find(ps.uid(i));
            if (k == ParticleStorage::kNotFound || !masters.flags(k).isMaster())
                return;
            s.shadows.push_back(
                {static_cast<std::uint32_t>(i), m->second, static_cast<std::uint32_t>(k)});
        }
    }
    m_valid = true;
}

bool UpdateList::unchanged(LocalParticles const& local) const {
    auto const blocks = local.blocks();
    if (!m_valid || blocks.size() != m_blocks.size())
        return false;
    for (std::size_t b = 0; b < blocks.size(); ++b)
        if (blocks[b].particles.layoutRevision() != m_blocks[b].revision)
            return false;
    return true;
}

UpdateList::Verdict UpdateList::check(LocalParticles const& local, double movedAtMost) {
    if (!unchanged(local) || !(m_budget > 0.0))
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
    m_largestMove = std::sqrt(largest);
    // Strictly within the budget, with room for the rounding of the distances the full
    // synchronisation compared (relative 1e-12, far below ParticleSync::kOverlapMargin).
    if (!(m_largestMove < m_budget * (1.0 - 1e-9)))
        return Verdict::Refresh;
    return left ? Verdict::Leavers : Verdict::Holds;
}

std::size_t UpdateList::update(LocalParticles& local) const {
    auto blocks = local.blocks();
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
    return updated;
}

bool UpdateList::reduce(LocalParticles& local, std::uint32_t stamp) const {
    if (!unchanged(local))
        return false;
    auto blocks = local.blocks();
    std::vector<HistoryEntry> entries;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        ParticleStorage& ps = blocks[b].particles;
        for (Shadow const& s : m_blocks[b].shadows) {
            sync_detail::touchedEntries(ps, s.index, stamp, entries);
            sync_detail::addShadowShare(ps, s.index, entries, blocks[s.masterBlock].particles,
                                        s.master);
        }
    }
    return true;
}

} // namespace regolith::particles
