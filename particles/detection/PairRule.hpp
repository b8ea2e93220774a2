#pragma once
/// The pair half of ContactDetector (see its class comment): the canonical geometry of two
/// copies and the contact-point rule that decides which block (and which image instance of the
/// pair) evaluates their contact. Inline, because the Verlet list's fused loop
/// (ContactDetector::detect with a pair callback) runs the geometry once per listed pair and
/// step, and must produce the same bits as the full rule.
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/DetectorConfig.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <cmath>
#include <cstddef>

namespace regolith::particles::detection_detail {

/// image(j) - image(i) per axis, unchecked (both are within +-kMaxImage, so it fits), plus
/// the pair's shift on the axes where the cells wrap (there both images are 0).
[[nodiscard]] inline CopyImage imageDifference(CopyImage const& kj, CopyImage const& ki,
                                               CopyImage const& shift = kNoImage) {
    CopyImage out{};
    for (std::size_t a = 0; a < 3; ++a)
        out[a] = static_cast<std::int8_t>(kj[a] - ki[a] + shift[a]);
    return out;
}

/// Where copies i, j (uid(i) < uid(j)) stand in i's canonical frame: j's shift, d = x_j +
/// shiftJ - x_i, |d|^2 and the contact reach r_i + r_j.
struct PairSeparation {
    core::Vec3 shiftJ;
    core::Vec3 d;
    double d2;
    double reach;
};

[[nodiscard, gnu::always_inline]] inline PairSeparation
separation(ParticleStorage const& ps, std::size_t i, std::size_t j, core::Vec3 const& period,
           CopyImage const& shift = kNoImage) {
    PairSeparation s;
    s.shiftJ = imageOffset(imageDifference(ps.image(j), ps.image(i), shift), period);
    // Always x_j + shiftJ (also for a zero shift), as ContactEvaluation computes it.
    s.d = (ps.position(j) + s.shiftJ) - ps.position(i);
    s.d2 = s.d.squaredNorm();
    s.reach = ps.radius(i) + ps.radius(j);
    return s;
}

/// The overlap decision of the canonical geometry: sqrt(d2) < reach + range (`range`: the
/// contact model's interaction range beyond touching, DetectorConfig::range), with sqrt correctly
/// rounded. The root is needed only in a thin band around contact: below reach^2 (1 - 1e-12)
/// the rounded root is certainly below reach, above reach^2 (1 + 1e-12) certainly not (the
/// margin dwarfs the few ulps by which reach * reach and the product can be off). Same answer
/// as the root everywhere, NaN included (false); the fused loop runs it on every listed pair
/// and step, and a root there is a long latency on the loop's path.
[[nodiscard, gnu::always_inline]] inline bool overlapping(PairSeparation const& s,
                                                          double range = 0.0) {
    double const reach = s.reach + range;
    double const r2 = reach * reach;
    if (s.d2 < r2 * (1.0 - 1e-12))
        return true;
    if (!(s.d2 <= r2 * (1.0 + 1e-12)))
        return false; // most listed pairs end here (and NaN)
    return std::sqrt(s.d2) < reach;
}

/// The canonical geometry of copies i, j (uid(i) < uid(j)): if |x_j + shiftJ - x_i| < r_i +
/// r_j + range, fills c (i, j, point, normal, penetration, shiftJ; the penetration negative,
/// minus the gap, for a pair within the range apart) and returns true. The one place these
/// bits are computed, so that every path (full rule, fused Verlet loop) agrees; a consumer of
/// PairOverlap that computes them itself (SpringDashpotBatch) follows these operations.
/// Always inlined: it runs once per listed pair and step.
[[nodiscard, gnu::always_inline]] inline bool
overlapGeometry(ParticleStorage const& ps, std::size_t i, std::size_t j, core::Vec3 const& period,
                Contact& c, double range = 0.0, CopyImage const& shift = kNoImage) {
    PairSeparation const s = separation(ps, i, j, period, shift);
    if (!overlapping(s, range))
        return false;
    double const dist = std::sqrt(s.d2);
    core::Vec3 const& d = s.d;
    double const ri = ps.radius(i);
    c.i = i;
    c.j = j;
    c.shiftJ = s.shiftJ;
    // Coincident centres have no direction; any unit normal is as good, this one is fixed.
    c.normal = dist > 0.0 ? core::Vec3(d / dist) : core::Vec3::UnitZ();
    c.penetration = s.reach - dist;
    c.point = ps.position(i) + (ri - 0.5 * c.penetration) * c.normal;
    return true;
}

/// The full rule for one candidate pair of copies: canonical order, geometry, Fixed pairs,
/// ownership point, periodic wrap and the evaluation region.
class PairRule {
public:
    /// `range`: the contact model's interaction range beyond touching (DetectorConfig::range).
    PairRule(ParticleStorage const& ps, core::AABB const& region, PeriodicFrame const& frame,
             DetectorStats& stats, double range = 0.0)
        : m_ps(ps)
        , m_region(region)
        , m_frame(frame)
        , m_period(frame.period())
        , m_stats(stats)
        , m_range(range) {}

    /// Tests candidate copies a and b (any order; b at `shift` from a beyond the images, on the
    /// wrapped axes); true (and `c` filled) if this block evaluates their contact.
    bool operator()(std::size_t a, std::size_t b, Contact& c,
                    CopyImage const& shift = kNoImage) const {
        ParticleStorage const& ps = m_ps;
        if (ps.uid(a) == ps.uid(b))
            return false; // a grain and its own periodic image
        std::size_t const i = ps.uid(a) < ps.uid(b) ? a : b;
        std::size_t const j = i == a ? b : a;
        if (!overlapGeometry(ps, i, j, m_period, c, m_range, i == a ? shift : negated(shift)))
            return false;
        ++m_stats.overlapsFound;
        if (ps.flags(i).isFixed() && ps.flags(j).isFixed())
            return false;
        return owns(c);
    }

    /// The rule for listed copies i, j in canonical order (uid(i) < uid(j)) known to overlap
    /// (OverlapScreen decided it with the same bits): not both Fixed, and the ownership point
    /// in this block. Counts nothing: the screen counted the overlap.
    [[nodiscard]] bool emitsOverlapping(std::size_t i, std::size_t j,
                                        CopyImage const& shift = kNoImage) const {
        ParticleStorage const& ps = m_ps;
        if (ps.flags(i).isFixed() && ps.flags(j).isFixed())
            return false;
        Contact c;
        return overlapGeometry(ps, i, j, m_period, c, m_range, shift) && owns(c);
    }

    /// Appends the contact of a and b to `out` if this block evaluates it.
    void operator()(std::size_t a, std::size_t b, std::vector<Contact>& out,
                    CopyImage const& shift = kNoImage) const {
        Contact c;
        if ((*this)(a, b, c, shift))
            out.push_back(c);
    }

    /// The contact-point rule for an overlapping pair.
    [[nodiscard]] bool owns(Contact const& c) const {
        ParticleStorage const& ps = m_ps;
        double const ri = ps.radius(c.i), rj = ps.radius(c.j);
        double const delta = c.penetration;
        // p = x_i + (r_i - delta/2) n lies r_i - delta/2 from x_i and r_j - delta/2 from x_j
        // along the normal: strictly between the two centres (so strictly inside both balls,
        // and inside the domain) while both are positive. Otherwise the overlap is at least the
        // smaller diameter and p lies behind the smaller centre, possibly outside an open
        // domain face where no block would evaluate the pair; that centre decides then.
        core::Vec3 q = c.point;
        if (!(ri - 0.5 * delta > 0.0 && rj - 0.5 * delta > 0.0))
            q = ri < rj ? ps.position(c.i) : core::Vec3(ps.position(c.j) + c.shiftJ);
        auto const [w, o] = m_frame.wrap(q);
        CopyImage const& ki = ps.image(c.i);
        for (std::size_t ax = 0; ax < 3; ++ax)
            if (ki[ax] != -o[ax] && !m_frame.wrapped[ax])
                return false; // another image instance of this pair (or another block)
        return m_region.contains(w);
    }

    [[nodiscard]] core::Vec3 const& period() const { return m_period; }
    [[nodiscard]] DetectorStats& stats() const { return m_stats; }

private:
    ParticleStorage const& m_ps;
    core::AABB const& m_region;
    PeriodicFrame const& m_frame;
    core::Vec3 m_period;
    DetectorStats& m_stats;
    double m_range;
};

} // namespace regolith::particles::detection_detail
