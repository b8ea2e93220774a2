#include "particles/detection/OverlapScreen.hpp"

#include "particles/storage/TransposedLoads.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace regolith::particles {

std::size_t OverlapScreen::lanes(ParticleStorage const& ps, core::Vec3 const& period,
                                 std::uint32_t const* is, std::uint32_t const* js, std::size_t n,
                                 bool oneImage) {
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
        for (std::size_t k = 0; k < n; ++k) {
            CopyImage const& ki = ps.image(is[k]);
            CopyImage const& kj = ps.image(js[k]);
            // imageOffset of the difference: an exact small integer times the period.
            m_sx[k] = static_cast<std::int8_t>(kj[0] - ki[0]) * period.x();
            m_sy[k] = static_cast<std::int8_t>(kj[1] - ki[1]) * period.y();
            m_sz[k] = static_cast<std::int8_t>(kj[2] - ki[2]) * period.z();
        }
        for (std::size_t k = 0; k < n; ++k) {
            double const dx = (m_xj[k] + m_sx[k]) - m_xi[k];
            double const dy = (m_yj[k] + m_sy[k]) - m_yi[k];
            double const dz = (m_zj[k] + m_sz[k]) - m_zi[k];
            double const d2 = dx * dx + dy * dy + dz * dz;
            m_overlap[k] = std::sqrt(d2) < m_reach[k];
        }
    }
    // The overlapping slots, from a bit per pair: eight flags at a time into eight bits (each
    // flag byte is 0 or 1, and the product puts byte b's bit at bit 56 + b without carries),
    // then one step per hit. A loop over the flags, with a branch-free append per pair, waited
    // on each flag's load behind the vector stores that wrote them.
    std::uint64_t overlapping = 0;
    for (std::size_t k = 0; k < n; k += 8) {
        std::uint64_t flags = 0;
        std::memcpy(&flags, &m_overlap[k], sizeof flags);
        overlapping |= ((flags * 0x0102040810204080ULL) >> 56) << k;
    }
    if (n < kCapacity)
        overlapping &= (std::uint64_t{1} << n) - 1; // (the flags past n are stale)
    std::size_t hits = 0;
    for (; overlapping != 0; overlapping &= overlapping - 1)
        m_hit[hits++] = static_cast<std::uint8_t>(std::countr_zero(overlapping));
    return hits;
}

} // namespace regolith::particles
