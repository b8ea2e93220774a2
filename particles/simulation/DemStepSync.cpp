// The synchronisation phase of DemStep::step: the step's agreement before the sync
// (StepAgreement.hpp: the motion bound, checked on every rank -- a grain that moved beyond the
// neighbour blocks is refused, by uid, on any layout --, the sync verdict, the Verlet lists'
// quiet motion), the kept springs written back where a copy may migrate, the sync itself, and
// the departures through open faces and walls counted.
#include "core/Error.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/simulation/StepAgreement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace regolith::particles {

namespace {

/// The largest step of the masters of `ps` that are still in the domain, dt |v| (the drift of
/// both integrators' position update, which leaves v at the velocity it moved with), over
/// `edge`, and in `fastest` the uid of the grain that took it (unchanged if none). Asked of a
/// block whose bound says a grain moved a block edge or more: one that left through an open
/// face is removed by the sync wherever it went, and only the others must stay within the
/// neighbour blocks.
double stayingShare(ParticleStorage const& ps, domain::ForestGeometry const& geometry, double dt,
                    double edge, Uid& fastest) {
    core::AABB const& box = geometry.domain();
    double largest = 0.0;
    ps.forEachMaster([&](std::size_t i) {
        core::Vec3 const& x = ps.position(i);
        for (int a = 0; a < 3; ++a)
            if (!geometry.periodic()[static_cast<std::size_t>(a)] &&
                !(x[a] >= box.min[a] && x[a] < box.max[a]))
                return; // leaves the domain
        double const share = dt * ps.velocity(i).norm() / edge;
        if (share > largest || !(share <= largest)) {
            largest = share;
            fastest = ps.uid(i);
        }
    });
    return largest;
}

} // namespace

void DemStep::syncParticles() {
    {
        auto const t = m_timers->scope(kSyncTimer);
        // This rank's share of the step's agreement before the sync (StepAgreement.hpp).
        BeforeSyncAgreement agreed{.moved = m_moved};
        auto const blocks = m_local->blocks();
        std::vector<Uid> fastest(m_movedSinceSync.size(), kInvalidUid);
        for (std::size_t b = 0; b < m_movedSinceSync.size(); ++b)
            if (m_movedSinceSync[b] >= 1.0 && std::isfinite(m_movedSinceSync[b]))
                m_movedSinceSync[b] =
                    stayingShare(blocks[b].particles, m_local->forest().geometry(), m_config.dt,
                                 m_reachEdge[b], fastest[b]);
        Uid mine = kInvalidUid; // the grain behind this rank's largest share, if measured
        for (std::size_t b = 0; b < m_movedSinceSync.size(); ++b)
            if (m_movedSinceSync[b] > agreed.share || !(m_movedSinceSync[b] <= agreed.share)) {
                agreed.share = m_movedSinceSync[b];
                agreed.edge = m_reachEdge[b];
                mine = fastest[b];
            }
        double const myShare = agreed.share;
        agreed.verdict = m_sync->verdictHere(*m_local, m_moved);
        if (m_comm->size() > 1)
            for (std::size_t b = 0; b < blocks.size(); ++b)
                agreed.quiet = std::min(agreed.quiet,
                                        m_detectors[b].quietMotion(blocks[b].particles,
                                                                   blocks[b].block->aabb, m_frame));
        agreed.reduce(*m_comm);
        // The lowest of every rank's `candidate` (kInvalidUid: none here). COLLECTIVE.
        auto const lowestUid = [this](Uid candidate) {
            auto const uids = m_comm->allGather<Uid>(candidate);
            return *std::min_element(uids.begin(), uids.end());
        };
        if (!std::isfinite(agreed.share)) { // LargestMove: +inf for a non-finite displacement
            // Every rank is here: the lowest uid of a master gone non-finite, on any layout.
            Uid worst = kInvalidUid;
            for (BlockParticles const& bp : blocks)
                bp.particles.forEachMaster([&](std::size_t i) {
                    ParticleStorage const& ps = bp.particles;
                    if (!(ps.position(i).allFinite() && ps.velocity(i).allFinite()))
                        worst = std::min(worst, ps.uid(i));
                });
            Uid const uid = lowestUid(worst);
            throw core::InputError(fmt::format(
                "step {}: {} position became non-finite: the motion is unstable; reduce "
                "time.dt or the contact stiffness",
                m_steps + 1,
                uid == kInvalidUid ? std::string("a grain's")
                                   : "particle uid " + std::to_string(uid) + "'s"));
        }
        if (!(agreed.share < 1.0)) {
            // Every rank is here (the shares are reduced): the uid from those that hold it.
            Uid const uid = lowestUid(myShare == agreed.share ? mine : kInvalidUid);
            throw core::InputError(fmt::format(
                "step {}: {} moved {:.6g} block edges in one step, beyond the neighbour "
                "blocks the synchronisation reaches (the smallest edge around it is {:.6g}): "
                "the motion is unstable or far too fast for time.dt; reduce time.dt (or the "
                "velocities, forces and stiffness that drive the grains)",
                m_steps + 1,
                uid == kInvalidUid ? std::string("a grain") : "particle uid " + std::to_string(uid),
                agreed.share, agreed.edge));
        }
        // A grain that may move skin / 2 from its list's reference may migrate or wrap in
        // this sync: that block's list shifts with the grains' drift, or the springs kept
        // beside it go back to the histories first.
        for (std::size_t b = 0; b < blocks.size(); ++b)
            m_detectors[b].beforeSync(blocks[b].particles, agreed.moved);
        try {
            m_sync->syncOn(*m_local, agreed.verdict);
        } catch (core::RankInputError const& e) { // found mid-sync by one rank: name the step
            throw core::RankInputError(fmt::format("step {}: {}", m_steps + 1, e.what()));
        }
        m_leftDomain += m_sync->lastStats().leftDomain;
        for (auto const& [uid, x] : m_sync->lastStats().departed)
            for (std::size_t w = 0; w < m_walls.size(); ++w)
                if (m_walls[w].distance(x) < 0.0) {
                    // The first step's lowest uid: the same grain on any layout.
                    std::uint64_t const count = m_wallCrossings.count + 1;
                    if (count == 1 || (m_wallCrossings.firstStep == m_steps + 1 &&
                                       uid < m_wallCrossings.firstUid))
                        m_wallCrossings = {count, uid, m_steps + 1, w};
                    m_wallCrossings.count = count;
                    break;
                }
        // The detectors' bound covers the copies of other ranks' masters too.
        m_listsQuiet = !agreed.listsMayComeDue();
        m_moved = agreed.moved;
        for (ContactDetector& d : m_detectors)
            d.noteMotion(m_moved);
        m_moved = 0.0;
        std::fill(m_movedSinceSync.begin(), m_movedSinceSync.end(), 0.0);
    }
    // One call per step keeps SOS-class grains converged after set-up.
    if (m_config.checkInvariants)
        requireSyncInvariants(*m_local, *m_comm, true,
                              "DemStep step " + std::to_string(m_steps + 1), copySkin());
}

} // namespace regolith::particles
