#include "particles/detection/OverlapScreen.hpp"

#include "particles/storage/TransposedLoads.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace regolith::particles {

namespace {

/// Bit k set where flags[k], k < n <= 64: eight flags at a time into eight bits (each flag
/// byte is 0 or 1, and the product puts byte b's bit at bit 56 + b without carries).
std::uint64_t maskOf(bool const* flags, std::size_t n) {
    std::uint64_t mask = 0;
    for (std::size_t k = 0; k < n; k += 8) {
        std::uint64_t eight = 0;
        std::memcpy(&eight, flags + k, sizeof eight);
        mask |= ((eight * 0x0102040810204080ULL) >> 56) << k;
    }
    if (n < 64)
        mask &= (std::uint64_t{1} << n) - 1; // (the flags past n are stale)
    return mask;
}

} // namespace

std::uint64_t OverlapScreen::lanes(ParticleStorage const& ps, core::Vec3 const& period,
                                   std::uint32_t const* is, std::uint32_t const* js, std::size_t n,
                                   bool oneImage, CopyImage const* shifts) {
    // Gather: centres four pairs at a time (transposed in registers), then the images (as
    // PairRule's imageDifference: the int8 difference) and the reach pair by pair.
    double const* const x = ps.positions().data()->data();
    std::size_t const n4 = n - n % 4;
    for (std::size_t k = 0; k < n4; k += 4) {
        lane_loads::transposed4(x, is + k, &m_xi[k], &m_yi[k], &m_zi[k]);
        lane_loads::transposed4(x, js + k, &m_xj[k], &m_yj[k], &m_zj[k]);
    }
    for (std::size_t k = n4; k < n; ++k) {
        core::Vec3 const& xi = ps.position(is[k]);
        core::Vec3 const& xj = ps.position(js[k]);
        m_xi[k] = xi.x();
        m_yi[k] = xi.y();
        m_zi[k] = xi.z();
        m_xj[k] = xj.x();
        m_yj[k] = xj.y();
        m_zj[k] = xj.z();
    }
    double const* const radius = ps.radii().data();
    for (std::size_t k = 0; k < n; ++k)
        m_reach[k] = radius[is[k]] + radius[js[k]];
    // separation (d = (x_j + shiftJ) - x_i, |d|^2 summed as Eigen's squaredNorm) and the
    // overlap decision with the correctly rounded root, branch-free: the loops vectorise.
    if (oneImage) {
        // shiftJ is +0.0, which changes d only where x_j is -0.0 (to +0.0): the same squares.
        for (std::size_t k = 0; k < n; ++k) {
            double const dx = m_xj[k] - m_xi[k];
            double const dy = m_yj[k] - m_yi[k];
            double const dz = m_zj[k] - m_zi[k];
            double const d2 = dx * dx + dy * dy + dz * dz;
            m_overlap[k] = std::sqrt(d2) < m_reach[k];
        }
    } else {
        if (shifts == nullptr) {
            for (std::size_t k = 0; k < n; ++k) {
                CopyImage const& ki = ps.image(is[k]);
                CopyImage const& kj = ps.image(js[k]);
                // imageOffset of the difference: an exact small integer times the period.
                m_sx[k] = static_cast<std::int8_t>(kj[0] - ki[0]) * period.x();
                m_sy[k] = static_cast<std::int8_t>(kj[1] - ki[1]) * period.y();
                m_sz[k] = static_cast<std::int8_t>(kj[2] - ki[2]) * period.z();
            }
        } else {
            for (std::size_t k = 0; k < n; ++k) {
                CopyImage const d =
                    detection_detail::imageDifference(ps.image(js[k]), ps.image(is[k]), shifts[k]);
                m_sx[k] = d[0] * period.x();
                m_sy[k] = d[1] * period.y();
                m_sz[k] = d[2] * period.z();
            }
        }
        for (std::size_t k = 0; k < n; ++k) {
            double const dx = (m_xj[k] + m_sx[k]) - m_xi[k];
            double const dy = (m_yj[k] + m_sy[k]) - m_yi[k];
            double const dz = (m_zj[k] + m_sz[k]) - m_zi[k];
            double const d2 = dx * dx + dy * dy + dz * dz;
            m_overlap[k] = std::sqrt(d2) < m_reach[k];
        }
    }
    // The overlapping slots, from a bit per pair. A loop over the flags, with a branch-free
    // append per pair, waited on each flag's load behind the vector stores that wrote them.
    return maskOf(m_overlap.data(), n);
}

std::uint64_t OverlapScreen::ruled(ParticleStorage const& ps, core::AABB const& region,
                                   PeriodicFrame const& frame, std::uint32_t const* is,
                                   std::uint32_t const* js, std::uint64_t pairs,
                                   std::uint64_t& unsure) {
    // The pairs to rule on, packed into lanes of their own (a block's pairs that keep the
    // rule and overlap are a fraction of it): the screen's centres and reach, the radii,
    // -image(i) per axis, and whether both copies are Fixed (1 or 0).
    RuleLanes& r = m_rule;
    double const* const radius = ps.radii().data();
    std::size_t n = 0;
    for (std::uint64_t left = pairs; left != 0; left &= left - 1, ++n) {
        auto const k = static_cast<std::size_t>(std::countr_zero(left));
        r.slot[n] = static_cast<std::uint8_t>(k);
        r.xi[0][n] = m_xi[k];
        r.xi[1][n] = m_yi[k];
        r.xi[2][n] = m_zi[k];
        r.xj[0][n] = m_xj[k] + m_sx[k];
        r.xj[1][n] = m_yj[k] + m_sy[k];
        r.xj[2][n] = m_zj[k] + m_sz[k];
        r.reach[n] = m_reach[k];
        r.ri[n] = radius[is[k]];
        r.rj[n] = radius[js[k]];
        CopyImage const& ki = ps.image(is[k]);
        for (std::size_t a = 0; a < 3; ++a)
            r.target[a][n] = -static_cast<double>(ki[a]);
        r.fixed[n] = ps.flags(is[k]).isFixed() && ps.flags(js[k]).isFixed() ? 1.0 : 0.0;
    }
    // Per axis, as wrapOnAxis takes them: the domain's bounds and extent, the clamp's top
    // (the largest value below max), the range the lanes decide in (within two periods, where
    // PeriodicFrame throws for none), and the region. A non-periodic axis as an infinite
    // periodic one of extent 0: every finite point inside, in image 0, w = q.
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::array<double, 3> lo{}, hi{}, extent{}, top{}, lowest{}, highest{}, rmin{}, rmax{};
    for (int a = 0; a < 3; ++a) {
        auto const u = static_cast<std::size_t>(a);
        bool const periodic = frame.periodic[u] && !frame.wrapped[u];
        lo[u] = periodic ? frame.domain.min[a] : -kInf;
        hi[u] = periodic ? frame.domain.max[a] : kInf;
        extent[u] = periodic ? hi[u] - lo[u] : 0.0;
        top[u] = std::nextafter(hi[u], lo[u]);
        lowest[u] = periodic ? lo[u] - 2.0 * extent[u] : -kInf;
        highest[u] = periodic ? hi[u] + 2.0 * extent[u] : kInf;
        rmin[u] = frame.wrapped[u] ? -kInf : region.min[a];
        rmax[u] = frame.wrapped[u] ? kInf : region.max[a];
    }
    // The conditions as selects between doubles (1 for true): GCC vectorises no logic on
    // bools here (their byte lanes need AVX-512BW).
    for (std::size_t k = 0; k < n; ++k) {
        // overlapGeometry: d, the normal, the penetration and the point, in its operations.
        double const d[3] = {r.xj[0][k] - r.xi[0][k], r.xj[1][k] - r.xi[1][k],
                             r.xj[2][k] - r.xi[2][k]};
        double const dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double const pen = r.reach[k] - dist;
        double const toPoint = r.ri[k] - 0.5 * pen;
        // owns: the point, or the smaller centre where the overlap reaches past it.
        double const toPointJ = r.rj[k] - 0.5 * pen;
        double own = r.fixed[k] != 0.0 ? 0.0 : 1.0, sure = 1.0;
#pragma GCC unroll 3
        for (std::size_t a = 0; a < 3; ++a) {
            double const unit = d[a] / dist;
            double const normal = dist > 0.0 ? unit : (a == 2 ? 1.0 : 0.0);
            double const point = r.xi[a][k] + toPoint * normal;
            double const centre = r.ri[k] < r.rj[k] ? r.xi[a][k] : r.xj[a][k];
            double const q = toPoint > 0.0 ? (toPointJ > 0.0 ? point : centre) : centre;
            // wrapOnAxis: image 0 inside [lo, hi), else the o with lo + o E <= q < lo +
            // (o + 1) E; the pair's instance is the one whose i is in image -o.
            double const t = r.target[a][k];
            double const low = lo[a] + t * extent[a], high = lo[a] + (t + 1.0) * extent[a];
            double w = q - t * extent[a];
            w = w < lo[a] ? lo[a] : w;
            w = w >= hi[a] ? top[a] : w;
            own = q >= lo[a] && q < hi[a] ? (t == 0.0 ? own : 0.0)
                                          : (q >= low && q < high ? own : 0.0);
            own = w >= rmin[a] && w < rmax[a] ? own : 0.0;
            sure = q >= lowest[a] && q < highest[a] ? sure : 0.0; // (0 if not finite)
        }
        r.emit[k] = own;
        r.sure[k] = sure;
    }
    std::uint64_t emit = 0;
    unsure = 0;
    for (std::size_t k = 0; k < n; ++k) {
        emit |= std::uint64_t{r.emit[k] != 0.0} << r.slot[k];
        unsure |= std::uint64_t{r.sure[k] == 0.0} << r.slot[k];
    }
    return emit;
}

} // namespace regolith::particles
