/// How the kept springs (ContactDetector's class comment, "Springs kept beside the list") get
/// into a Verlet list, and across a rebuild ("Springs carried across a rebuild"): which springs
/// stay beside the list over the synchronisation before a rebuild, how the rebuilt list takes
/// them, and where the rest go.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace regolith::particles {

void ContactDetector::markStaying(ParticleStorage const& ps) {
    // Inside the box where the rule emits (the region, and the domain on periodic axes) by 4 x
    // the candidate slack, classifyListed's rounding of the ownership point.
    double const margin = 4.0 * m_stats.slack;
    core::Vec3 const lo = m_emits.min + core::Vec3::Constant(margin);
    core::Vec3 const hi = m_emits.max - core::Vec3::Constant(margin);
    auto const& x = ps.positions();
    m_staying.resize(ps.size());
    for (std::size_t k = 0, n = ps.size(); k < n; ++k) {
        bool const inside = x[k].x() > lo.x() && x[k].x() < hi.x() && x[k].y() > lo.y() &&
                            x[k].y() < hi.y() && x[k].z() > lo.z() && x[k].z() < hi.z();
        m_staying[k] = inside && ps.flags(k).isMaster() && isZero(ps.image(k)) ? 1 : 0;
    } // (not finite: not inside)
}

void ContactDetector::writeBackMovable(ParticleStorage& ps) {
    if (m_list.numKept() == 0)
        return;
    markStaying(ps);
    m_list.forEachPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (keepsSpring(m_list.mode(p)) && !(m_staying[i] && m_staying[j]))
            writeBackSpring(ps, i, ps.uid(j), m_list.spring(p), m_list.hint(p));
    });
    m_movableWrittenBack = true;
}

void ContactDetector::carrySprings(ParticleStorage& ps, core::AABB const& region,
                                   PeriodicFrame const& frame) {
    m_carried.clear();
    m_carriedListed.clear();
    bool const movableWrittenBack = m_movableWrittenBack;
    if (!listedFor(region, frame)) { // the staying copies answer for the list's region only
        writeBackSprings(ps);
        return;
    }
    if (!m_springsLive)
        return;
    m_springsLive = false;
    if (m_list.numKept() == 0)
        return;
    markStaying(ps);
    // Carried, in list order: the springs of the last pass, and those never touched (their
    // histories hold no entry: the fill would find none), between two staying copies. Written
    // back: those touched before the last pass, and, unless beforeSync wrote them back before
    // the synchronisation (unchanged since), the others.
    std::vector<CarriedPair>& listed = m_carriedListed; // (reused: no allocation per rebuild)
    listed.clear();
    m_list.forEachPair([&](std::size_t i, std::size_t j, std::size_t p) {
        if (!keepsSpring(m_list.mode(p)))
            return;
        KeptSpring const& kept = m_list.spring(p);
        bool const staying = m_staying[i] && m_staying[j];
        if (staying && (kept.stamp == m_pass || kept.stamp == KeptSpring::kUntouched))
            listed.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j),
                              static_cast<std::uint32_t>(p)});
        else if (staying || !movableWrittenBack)
            writeBackSpring(ps, i, ps.uid(j), kept, m_list.hint(p));
    });
    if (!movableWrittenBack) // a face pair written back after the sync: its images need it too
        for (FaceTwin const& t : m_twins)
            if (!(m_staying[m_list.indexOf(t.a)] && m_staying[m_list.indexOf(t.b)]))
                writeBackFaceTwin(ps, t);
    m_list.swapSprings(m_carriedSprings, m_carriedHints); // the rebuild restarts the list
}

void ContactDetector::indexCarried(ParticleStorage const& ps) {
    // By the rank of canonical i in the new list's cell order, counting (no sort): the fill
    // visits the pairs cell by cell, so the carried pairs it looks up next lie close together.
    std::vector<std::uint32_t>& rank = m_carriedRank;
    rank.assign(ps.size(), 0);
    std::uint32_t r = 0;
    for (std::uint32_t k : m_cells.membersInCellOrder())
        rank[k] = r++;
    for (std::size_t k : m_large)
        rank[k] = r++;
    m_carriedFrom.assign(ps.size() + 1, 0);
    for (CarriedPair const& c : m_carriedListed)
        ++m_carriedFrom[rank[c.i] + 1];
    for (std::size_t k = 1; k < m_carriedFrom.size(); ++k)
        m_carriedFrom[k] += m_carriedFrom[k - 1];
    m_carried.resize(m_carriedListed.size());
    for (CarriedPair const& c : m_carriedListed)
        m_carried[m_carriedFrom[rank[c.i]]++] = c;
    std::copy_backward(m_carriedFrom.begin(), m_carriedFrom.end() - 1, m_carriedFrom.end());
    m_carriedFrom[0] = 0; // (back to the starts)
    m_carriedListed.clear();
}

void ContactDetector::fillKeptSprings(ParticleStorage const& ps, std::size_t first) {
    if (m_list.numKept() == 0) {
        m_springsLive = true;
        return;
    }
    bool const carried = !m_carriedListed.empty();
    if (carried)
        indexCarried(ps);
    m_list.forEachPair(
        [&](std::size_t i, std::size_t j, std::size_t p) {
            if (!keepsSpring(m_list.mode(p)))
                return;
            if (carried) { // from the list before the rebuild
                std::uint32_t const r = m_carriedRank[i];
                for (std::uint32_t c = m_carriedFrom[r], end = m_carriedFrom[r + 1]; c < end; ++c)
                    if (m_carried[c].j == j && m_carried[c].i == i) {
                        m_list.spring(p) = m_carriedSprings[m_carried[c].pair];
                        m_list.hint(p) = m_carriedHints[m_carried[c].pair];
                        m_carried[c].j = CarriedPair::kTaken;
                        ++m_stats.springsCarried;
                        return;
                    }
            }
            ContactHistory const& history = ps.history(i);
            HistoryEntry const* e = history.find(ps.uid(j));
            m_list.spring(p) = e != nullptr ? KeptSpring{e->spring, e->stamp} : KeptSpring{};
            if (e != nullptr) // the slot, for writeBackSpring (a hint: verified there)
                m_list.hint(p) =
                    static_cast<std::uint8_t>(std::min<std::ptrdiff_t>(e - history.begin(), 255));
        },
        first);
    m_springsLive = true;
}

void ContactDetector::writeBackCarried(ParticleStorage& ps) {
    // The new list keeps none of these pairs: the pass reads their springs from the histories.
    // (Indexed by the fill, or, without one, still in list order.)
    for (auto* carried : {&m_carried, &m_carriedListed}) {
        for (CarriedPair const& c : *carried) {
            KeptSpring const& kept = m_carriedSprings[c.pair];
            if (c.j != CarriedPair::kTaken && kept.stamp != KeptSpring::kUntouched) {
                writeBackSpring(ps, c.i, ps.uid(c.j), kept, m_carriedHints[c.pair]);
                ++m_stats.springsCarriedBack;
            }
        }
        carried->clear();
    }
}

} // namespace regolith::particles
