// Whether next-neighbour synchronisation can simulate the scene (ParticleSync's
// findNnsViolation and requireNnsApplicable): every grain, grown by the sync skin, below the
// smallest edge of the blocks it may touch (the paper's Alg. 1 reaches next neighbours only).
#include "core/Error.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncEngine.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace regolith::particles {

std::optional<NnsViolation> ParticleSync::findNnsViolation(LocalParticles const& local) const {
    std::optional<NnsViolation> first;
    bool radiusAlone = false;
    double skinBound = std::numeric_limits<double>::infinity();
    for (BlockParticles const& bp : local.blocks()) {
        double const edge = m_impl->edgeAround(bp.block->id.raw());
        ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            double const r = ps.radius(i);
            if (!(r + m_config.skin + 0.5 * m_config.reach >= edge))
                return;
            radiusAlone = radiusAlone || r >= edge;
            skinBound = std::min(skinBound, edge - r);
            if (!first || ps.uid(i) < first->uid)
                first = NnsViolation{ps.uid(i), r, edge};
        });
    }
    if (first) {
        first->radiusAlone = radiusAlone;
        first->skinBound = skinBound;
    }
    return first;
}

void ParticleSync::requireNnsApplicable(LocalParticles const& local) const {
    if (m_config.method != SyncMethod::NextNeighbour)
        return;
    auto const v = findNnsViolation(local);
    core::Comm const& comm = m_impl->comm();
    auto const uids = comm.allGather<std::uint64_t>(v ? v->uid : kInvalidUid);
    auto const radii = comm.allGather<double>(v ? v->radius : 0.0);
    auto const edges = comm.allGather<double>(v ? v->blockEdge : 0.0);
    auto const first = std::min_element(uids.begin(), uids.end());
    if (*first == kInvalidUid)
        return;
    auto const at = static_cast<std::size_t>(first - uids.begin());
    // Every violator over all ranks: the skin is the cause only if each would pass without it,
    // and the bound is the smallest of their margins.
    bool const radiusAlone = comm.allReduce(v && v->radiusAlone ? 1 : 0, core::ReduceOp::Max) != 0;
    double const skinBound = comm.allReduce(
        v ? v->skinBound : std::numeric_limits<double>::infinity(), core::ReduceOp::Min);
    // The boxes NNS reaches: blocks, or each rank's blocks merged (sync.subdomains).
    bool const merged = m_impl->forest().subdomains() == domain::Subdomains::RankBoxes;
    char const* const boxes = merged ? "subdomains" : "blocks";
    std::ostringstream msg;
    if (m_config.skin > 0.0 && !radiusAlone)
        msg << "sync.skin = " << m_config.skin << ": with sync.method = \"nns\", particle uid "
            << *first << "'s radius " << radii[at] << " plus the skin is not below the smallest "
            << "edge " << edges[at] << " of the " << boxes
            << " it may touch (NNS only reaches next "
            << "neighbours); reduce sync.skin below " << skinBound
            << ", or use sync.method = \"sos\" or \"hybrid\"";
    else
        msg << "sync.method = \"nns\" cannot simulate this scene: particle uid " << *first
            << " has radius " << radii[at] << (m_config.skin > 0.0 ? " plus sync.skin" : "")
            << ", not below the smallest edge " << edges[at] << " of the " << boxes
            << " it may touch (NNS only reaches next neighbours); use "
            << "sync.method = \"sos\" or \"hybrid\", or larger blocks"
            << (merged ? " or fewer ranks (a rank's blocks form its subdomains)" : "");
    throw core::InputError(msg.str());
}

} // namespace regolith::particles
