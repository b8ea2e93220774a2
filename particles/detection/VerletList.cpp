#include "particles/detection/VerletList.hpp"

#include "core/Error.hpp"
#include "core/memory/GentleGrowth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace regolith::particles {

void VerletList::restart(ParticleStorage& ps, double skin) {
    if (ps.size() >= kDead - 1)
        throw core::Error("VerletList: too many copies for 32-bit ids");
    m_session = ps.startTracing();
    m_storage = &ps;
    m_live.stale = true;
    m_skin = skin;
    m_moved = 0.0;
    m_built = ps.size();
    m_pairs.clear();
    m_shift.clear();
    m_gap.clear();
    m_apart = 0;
    m_parked.clear();
    m_owned = 0;
    m_kept = 0;
    m_pressed = 0;
    m_mode.clear();
    m_hint.clear();
    m_springs.clear();
    m_arrivals.clear();
    // Room for the copies that arrive before the next rebuild (follow), so that the first
    // arrival does not reallocate these per-copy arrays: a reallocation holds the old and
    // the new array at once, 28 more bytes per copy at that moment (the run's peak).
    m_indexOf.reserve(core::gentleCapacity(m_built));
    m_reference.reserve(core::gentleCapacity(m_built));
    m_indexOf.resize(m_built);
    for (std::size_t k = 0; k < m_built; ++k)
        m_indexOf[k] = static_cast<std::uint32_t>(k);
    // The origin in the middle of the copies: the smallest coordinates to round.
    core::Vec3 lo = core::Vec3::Constant(std::numeric_limits<double>::infinity());
    core::Vec3 hi = -lo;
    for (core::Vec3 const& x : ps.positions())
        if (x.allFinite()) {
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
        }
    m_origin = m_built != 0 && lo.x() <= hi.x() ? core::Vec3(0.5 * (lo + hi)) : core::Vec3::Zero();
    m_builtOrigin = m_origin;
    m_common = core::Vec3::Zero();
    m_extent = 0.0;
    m_referenceSlack = 0.0;
    m_reference.clear();
    for (core::Vec3 const& x : ps.positions())
        pushReference(x);
    m_hole = static_cast<Id>(m_built); // the arrivals' ids follow it
    m_indexOf.push_back(kDead);
    m_reference.push_back({0.0F, 0.0F, 0.0F});
}

void VerletList::pushReference(core::Vec3 const& x) {
    core::Vec3 const d = x - m_origin;
    m_reference.push_back(
        {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())});
    double const far = d.cwiseAbs().maxCoeff();
    if (far > m_extent) { // false for NaN: movedTooFar reports those
        m_extent = far;
        widenSlack();
    }
}

void VerletList::widenSlack() {
    // Per coordinate: x - origin rounds by <= u |d|, the float by <= 2^-24 |d|, origin + f by
    // <= u (|origin| + |d|) (u = 2^-53); doubled for the three coordinates (sqrt 3 < 2) and
    // the rest for good measure. Never narrowed: the budget only shrinks.
    double const u = 0x1p-53;
    double const o = m_origin.cwiseAbs().maxCoeff();
    m_referenceSlack =
        std::max(m_referenceSlack, 2.0 * (0x1p-23 * m_extent + 4.0 * u * (o + m_extent)));
}

VerletList::Displacements VerletList::displacements(ParticleStorage const& ps) const {
    auto const& x = ps.positions();
    core::Vec3 lo = core::Vec3::Constant(std::numeric_limits<double>::infinity());
    core::Vec3 hi = -lo;
    double largest = 0.0, largestMaster = 0.0;
    bool finite = true;
    auto const flags = ps.allFlags();
    for (std::size_t k = 0, n = ps.size(); k < n; ++k) {
        Reference const& r = m_reference[ps.traceTag(k)];
        core::Vec3 const d =
            (x[k] - m_origin) - core::Vec3(double{r[0]}, double{r[1]}, double{r[2]});
        double const d2 = d.squaredNorm();
        finite = finite & !std::isnan(d2);
        largest = std::max(largest, d2);
        largestMaster = std::max(largestMaster, flags[k].isMaster() ? d2 : 0.0);
        lo = lo.cwiseMin(d);
        hi = hi.cwiseMax(d);
    }
    Displacements out;
    out.finite = finite && std::isfinite(largest);
    if (ps.size() == 0 || !out.finite)
        return out;
    out.largest = std::sqrt(largest);
    out.largestMaster = std::sqrt(largestMaster);
    out.drift = 0.5 * (lo + hi); // the centre of the bounding box
    return out;
}

double VerletList::spread(ParticleStorage const& ps, core::Vec3 const& drift) const {
    // The farthest displacement from the drift (at most half the bounding box's diagonal,
    // often much less).
    auto const& x = ps.positions();
    core::Vec3 const centre = m_origin + drift;
    double farthest = 0.0;
    for (std::size_t k = 0, n = ps.size(); k < n; ++k) {
        Reference const& r = m_reference[ps.traceTag(k)];
        core::Vec3 const d = (x[k] - centre) - core::Vec3(double{r[0]}, double{r[1]}, double{r[2]});
        farthest = std::max(farthest, d.squaredNorm());
    }
    return std::sqrt(farthest) * (1.0 + 1e-12);
}

void VerletList::shift(core::Vec3 const& drift, double moved) {
    m_origin += drift;
    m_common -= drift;
    widenSlack(); // reference() now adds a larger origin
    m_moved = moved + m_referenceSlack;
}

void VerletList::refreshLive() const {
    // Every pair written, the count advanced past the live ones: no branch per pair (a dead
    // copy or a parked pair's hole is rare, but the capacity checks of an append are not).
    std::size_t const n = m_pairs.size();
    m_live.a.resize(n);
    m_live.b.resize(n);
    m_live.at.resize(n);
    std::uint32_t* const a = m_live.a.data();
    std::uint32_t* const b = m_live.b.data();
    std::uint32_t* const at = m_live.at.data();
    std::size_t live = 0;
    for (std::size_t p = 0; p < n; ++p) {
        std::uint32_t const ka = m_indexOf[m_pairs[p][0]], kb = m_indexOf[m_pairs[p][1]];
        a[live] = ka;
        b[live] = kb;
        at[live] = static_cast<std::uint32_t>(p);
        live += ka != kDead && kb != kDead ? 1 : 0;
    }
    m_live.a.resize(live);
    m_live.b.resize(live);
    m_live.at.resize(live);
    m_live.stale = false;
}

bool VerletList::follow(ParticleStorage& ps, std::vector<std::size_t>& fresh) {
    fresh.clear();
    if (m_storage != &ps || ps.traceSession() != m_session || ps.traceBroken())
        return false;
    auto const journal = ps.traceJournal();
    m_live.stale = m_live.stale || !journal.empty();
    // The ids of every written slot die ... unless they turn up in another written slot.
    for (TraceChange const& c : journal)
        if (c.previous != ParticleStorage::kUntraced)
            m_indexOf[c.previous] = kDead;
    std::size_t const n = ps.size();
    for (TraceChange const& c : journal) {
        if (c.index >= n)
            continue; // dropped from the end
        Id id = ps.traceTag(c.index);
        if (id == ParticleStorage::kUntraced) {
            if (m_indexOf.size() >= kDead)
                return false; // out of ids: rebuild
            id = static_cast<Id>(m_indexOf.size());
            ps.setTraceTag(c.index, id);
            core::reserveForAppend(m_indexOf); // per-copy arrays sized at restart: no doubling
            core::reserveForAppend(m_reference);
            m_indexOf.push_back(kDead);
            // Referenced as if it had moved with the others since their references: their
            // common displacement, which the bound must then cover.
            pushReference(ps.position(c.index) - m_common);
            if (!m_common.isZero())
                m_moved = std::max(m_moved, m_common.norm() + m_referenceSlack);
            m_arrivals.push_back(id);
            fresh.push_back(c.index);
        }
        m_indexOf[id] = c.index;
    }
    ps.clearTraceJournal();
    return true;
}

namespace {
/// The bound on every copy's distance from its reference after a move of `movedAtMost`.
double boundAfter(double moved, double movedAtMost) {
    return moved + (movedAtMost >= 0.0 ? movedAtMost : std::numeric_limits<double>::infinity());
}
} // namespace

bool VerletList::mayMoveTooFar(double movedAtMost, double share) const {
    // Within skin / 2 of the true reference if within skin / 2 - slack of the stored one.
    double const half = budget();
    // The bound is on the true positions; the slack also covers a shadow's rounding when its
    // master's position is shifted by a period (a few ulps, not growing with the steps), and
    // the relative 1e-9 the rounding of the sum.
    return !(half > 0.0) || !(boundAfter(m_moved, movedAtMost) * (1.0 + 1e-9) < share * half);
}

double VerletList::quietMotion() const {
    // movedAtMost <= room: (m_moved + movedAtMost) (1 + 1e-9) <= budget (1 - 1e-6) (1 + 1e-9)
    // plus a few roundings of the budget's size, below the budget: mayMoveTooFar is false.
    // Without a budget (no skin: an empty block's list) movedTooFar is true at any motion.
    double const half = budget();
    double const room = half * (1.0 - 1e-6) - m_moved;
    return half > 0.0 && room >= 0.0 && std::isfinite(room)
               ? room
               : -std::numeric_limits<double>::infinity();
}

bool VerletList::movedTooFar(ParticleStorage const& ps, double movedAtMost, double share) {
    double const half = budget();
    if (!(half > 0.0))
        return true;
    bool const compare = mayMoveTooFar(movedAtMost, share);
    m_moved = boundAfter(m_moved, movedAtMost);
    if (!compare)
        return false;
    auto const& x = ps.positions();
    double largest = 0.0;
    bool finite = true;
    for (std::size_t k = 0, n = ps.size(); k < n; ++k) {
        Reference const& r = m_reference[ps.traceTag(k)];
        core::Vec3 const d =
            (x[k] - m_origin) - core::Vec3(double{r[0]}, double{r[1]}, double{r[2]});
        double const d2 = d.squaredNorm();
        finite = finite & !std::isnan(d2); // no early exit: the loop stays branch-free
        largest = std::max(largest, d2);
    }
    double const moved = std::sqrt(largest);
    m_moved = moved + m_referenceSlack;
    return !finite || !(moved < half);
}

float VerletList::nearReach() const {
    // Each copy lies within moved() of its reference, which lies within the reference slack
    // of where it stood when its pair's gap was measured.
    return core::floatNotBelow(2.0 * (m_moved + m_referenceSlack));
}

std::size_t VerletList::bytes() const {
    return m_pairs.capacity() * sizeof(m_pairs[0]) + m_shift.capacity() * sizeof(CopyImage) +
           m_gap.capacity() * sizeof(float) + m_mode.capacity() + m_hint.capacity() +
           m_springs.capacity() * sizeof(KeptSpring) +
           m_indexOf.capacity() * sizeof(std::uint32_t) +
           m_reference.capacity() * sizeof(Reference) + m_arrivals.capacity() * sizeof(Id) +
           (m_parked.capacity() + m_parkedAgain.capacity()) * sizeof(m_parked[0]) +
           m_trailing.capacity() * sizeof(TrailingPair) +
           (m_live.a.capacity() + m_live.b.capacity() + m_live.at.capacity()) *
               sizeof(std::uint32_t);
}

} // namespace regolith::particles
