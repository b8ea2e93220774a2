// When ContactDetector's Verlet list is rebuilt: the decision before each mutable detect
// (updateList), made ahead of it where the ranks agree on their rebuilds (prepareList), and the
// motion under which it cannot come due (quietMotion), so that the ranks need not agree then.
#include "core/Error.hpp"
#include "particles/detection/ContactDetector.hpp"

#include <limits>
#include <utility>

namespace regolith::particles {

bool ContactDetector::listedFor(core::AABB const& region, PeriodicFrame const& frame) const {
    // The settled pairs (classifyListed) hold for one region and frame only.
    return region.min == m_listRegion.min && region.max == m_listRegion.max &&
           frame.domain.min == m_listFrame.domain.min &&
           frame.domain.max == m_listFrame.domain.max && frame.periodic == m_listFrame.periodic;
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

} // namespace regolith::particles
