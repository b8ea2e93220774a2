// When ContactDetector's Verlet list is rebuilt: the decision before each mutable detect
// (updateList), made ahead of it where the ranks agree on their rebuilds (prepareList), and the
// motion under which it cannot come due (quietMotion), so that the ranks need not agree then;
// between rebuilds, the pairs of the copies that arrived (addArrivals).
#include "core/Error.hpp"
#include "particles/detection/ContactDetector.hpp"

#include <cstdint>
#include <limits>
#include <utility>

namespace regolith::particles {

bool ContactDetector::listedFor(core::AABB const& region, PeriodicFrame const& frame) const {
    // The settled pairs (classifyListed) hold for one region and frame only.
    return region.min == m_listRegion.min && region.max == m_listRegion.max &&
           frame.domain.min == m_listFrame.domain.min &&
           frame.domain.max == m_listFrame.domain.max && frame.periodic == m_listFrame.periodic &&
           frame.wrapped == m_listFrame.wrapped;
}

bool ContactDetector::tooManyArrivals() const {
    return m_list.arrivals().size() > 64 + m_list.builtSize() / 16;
}

double ContactDetector::quietMotion(ParticleStorage const& ps, core::AABB const& region,
                                    PeriodicFrame const& frame) const {
    if (!listed() || m_config.sortByUid)
        return std::numeric_limits<double>::infinity(); // prepareList decides nothing
    // decideRebuild's other reasons, none of which a bound on the motion rules out.
    if (!listedFor(region, frame) || !m_list.followsUnchanged(ps) || tooManyArrivals())
        return -std::numeric_limits<double>::infinity();
    return m_list.quietMotion();
}

ContactDetector::ListOutlook ContactDetector::prepareList(ParticleStorage& ps,
                                                          core::AABB const& region,
                                                          PeriodicFrame const& frame,
                                                          bool halfwayNeeded) {
    if (!listed() || m_config.sortByUid)
        return {}; // detect uses no list
    decideRebuild(ps, region, frame, halfwayNeeded ? kHalfway : 1.0);
    m_prepared = true;
    return {m_rebuildDue, m_rebuildDue || m_list.moved() >= kHalfway * m_list.budget()};
}

void ContactDetector::decideRebuild(ParticleStorage& ps, core::AABB const& region,
                                    PeriodicFrame const& frame, double share) {
    double const moved = std::exchange(m_movedAtMost, std::numeric_limits<double>::infinity());
    bool const follows = m_list.follow(ps, m_fresh);
    if (!follows && m_springsLive)
        throw core::Error("contact detection: the storage changed beyond the Verlet list's "
                          "trace while it kept springs that were not written back");
    m_listedBefore = m_list.numPairs();
    if (follows && listedFor(region, frame) && !tooManyArrivals())
        shiftAhead(ps, moved);
    m_rebuildDue = !listedFor(region, frame) || !follows || tooManyArrivals() ||
                   m_list.movedTooFar(ps, moved, share) || !addArrivals(ps, region, frame);
}

void ContactDetector::updateList(ParticleStorage& ps, core::AABB const& region,
                                 PeriodicFrame const& frame) {
    if (!std::exchange(m_prepared, false))
        decideRebuild(ps, region, frame, 1.0);
    bool const rebuild = m_rebuildDue;
    if (rebuild) {
        // While the list still follows the storage. Carrying costs passes over every kept
        // pair, the histories two scattered look-ups per spring that touched: a gas, whose
        // kept pairs mostly stand apart, writes them back (the last pass's overlaps count).
        if (m_springsLive && 4 * m_stats.overlapsFound >= m_list.numKept())
            carrySprings(ps);
        else
            writeBackSprings(ps);
        rebuildList(ps, region, frame);
    }
    m_fillFrom = m_springsLive && !rebuild ? m_listedBefore : 0;
    m_stats.rebuilt = rebuild;
    m_stats.shifts = std::exchange(m_shifts, 0);
    m_stats.arrivals = rebuild ? 0 : m_fresh.size();
    m_stats.overlapsFound = 0;
    m_stats.listedPairs = m_list.numPairs();
    m_stats.settledPairs = m_list.numOwned();
    m_stats.keptPairs = m_list.numKept();
    m_stats.pressedPairs = m_list.numPressed();
}

bool ContactDetector::addArrivals(ParticleStorage const& ps, core::AABB const& region,
                                  PeriodicFrame const& frame) {
    core::Vec3 const period = frame.period();
    std::size_t const firstPair = m_list.numPairs();
    // Both sides of a test are references, each within the reference slack of the position it
    // stands for.
    double const referenceSlack = m_list.referenceSlack();
    double const reachSlack = m_stats.slack + m_listSkin + 2.0 * referenceSlack + m_config.range;
    auto const arrivals = m_list.arrivals();
    std::size_t const firstNew = arrivals.size() - m_fresh.size();
    core::Vec3 const drift = m_list.drift();
    // Local reference position and radius of a live id (its image is that of its copy now).
    auto referenceOf = [&](VerletList::Id id, std::size_t k) {
        return localPosition(m_list.reference(id), ps.image(k), period);
    };
    // Each fresh copy is tested against every arrival before it: their reference positions
    // and radii once, in lanes (x, y, z, r).
    std::size_t const na = arrivals.size();
    m_arrivalLanes.resize(4 * na);
    m_arrivalHits.resize(na);
    double* const ax = m_arrivalLanes.data();
    double* const ay = ax + na;
    double* const az = ay + na;
    double* const ar = az + na;
    std::uint8_t* const hit = m_arrivalHits.data();
    for (std::size_t e = 0; e < na && !frame.anyWrapped(); ++e) { // (test() where they wrap)
        std::uint32_t const k = m_list.indexOf(arrivals[e]);
        bool const live = k != VerletList::kDead;
        core::Vec3 const x = live ? referenceOf(arrivals[e], k) : core::Vec3::Zero();
        ax[e] = x.x();
        ay[e] = x.y();
        az[e] = x.z();
        ar[e] = live ? ps.radius(k) : std::numeric_limits<double>::quiet_NaN();
    }
    for (std::size_t n = 0; n < m_fresh.size(); ++n) {
        std::size_t const f = m_fresh[n];
        VerletList::Id const idF = VerletList::idOf(ps, f);
        // Its reference: where it stands less the copies' common displacement (VerletList::
        // follow), so that it moves with them.
        core::Vec3 const xf = referenceOf(idF, f);
        double const rf = ps.radius(f);
        if (!(xf.cwiseAbs().maxCoeff() + 2.0 * rf <= m_listScale))
            return false; // beyond the rounding slack of the last rebuild (or not finite)
        auto test = [&](VerletList::Id id) {
            std::uint32_t const k = m_list.indexOf(id);
            if (k == VerletList::kDead)
                return;
            double const reach = rf + ps.radius(k) + reachSlack;
            core::Vec3 const x = referenceOf(id, k);
            frame.forEachWrappedImage(xf - x, reach, [&](CopyImage const& shift) {
                if ((localPosition(x, shift, period) - xf).squaredNorm() < reach * reach)
                    m_list.addPair(idF, id, VerletList::kNoGap, shift);
            });
        };
        // The cells hold the small spheres' local positions at the rebuild, by id: their
        // references less the list's drift since (VerletList::shift). Where they wrap, the
        // query's images find the ids across the faces, each with its shift.
        m_cells.forEachOverlapWith(
            xf - drift, rf + referenceSlack, [&](std::uint32_t id, CopyImage shift) {
                if (m_list.indexOf(static_cast<VerletList::Id>(id)) != VerletList::kDead)
                    m_list.addPair(idF, static_cast<VerletList::Id>(id), VerletList::kNoGap, shift);
            });
        for (VerletList::Id id : m_largeIds)
            test(id);
        // The arrivals before this one: test's operations over the lanes (a dead one's reach
        // is NaN, which no distance is below), then the hits in order.
        std::size_t const earlier = firstNew + n;
        if (frame.anyWrapped()) { // the earlier arrivals' images across the wrapped faces
            for (std::size_t e = 0; e < earlier; ++e)
                if (m_list.indexOf(arrivals[e]) != VerletList::kDead)
                    test(arrivals[e]);
            continue;
        }
        for (std::size_t e = 0; e < earlier; ++e) {
            double const dx = ax[e] - xf.x(), dy = ay[e] - xf.y(), dz = az[e] - xf.z();
            double const reach = (rf + ar[e]) + reachSlack;
            hit[e] = (dx * dx + dy * dy) + dz * dz < reach * reach ? 1 : 0;
        }
        for (std::size_t e = 0; e < earlier; ++e)
            if (hit[e] != 0)
                m_list.addPair(idF, arrivals[e]);
    }
    classifyListed(ps, region, frame, firstPair);
    return true;
}

} // namespace regolith::particles
