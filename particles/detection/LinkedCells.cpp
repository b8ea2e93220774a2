#include "particles/detection/LinkedCells.hpp"

#include "core/Error.hpp"
#include "core/math/FloatBounds.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace regolith::particles {

void LinkedCells::build(LocalPositions const& positions, std::span<double const> radii,
                        std::span<std::uint32_t const> members, double minEdge,
                        std::size_t maxCells, double slack) {
    m_member.clear();
    m_x.clear();
    m_y.clear();
    m_z.clear();
    m_radius.clear();
    m_start.clear();
    m_maxRadius = 0.0;
    m_slack = slack;
    m_roundingSlack = 0.0;
    m_testSlack = slack;
    m_dims = {0, 0, 0};
    if (members.empty())
        return;
    if (members.size() >= std::numeric_limits<std::uint32_t>::max())
        throw core::Error("LinkedCells: " + std::to_string(members.size()) +
                          " spheres exceed the 32-bit slot index");

    core::Vec3 lo = positions[members[0]], hi = lo;
    for (std::size_t k : members) {
        lo = lo.cwiseMin(positions[k]);
        hi = hi.cwiseMax(positions[k]);
        m_maxRadius = std::max(m_maxRadius, radii[k]);
    }
    if (!lo.allFinite() || !hi.allFinite())
        throw core::Error("LinkedCells: a sphere centre is not finite");
    if (!(slack >= 0.0) || !std::isfinite(slack))
        throw core::Error("LinkedCells: slack " + std::to_string(slack) +
                          " is not non-negative and finite");
    if (!(minEdge > 0.0) || !std::isfinite(minEdge))
        throw core::Error("LinkedCells: cell edge " + std::to_string(minEdge) +
                          " is not positive and finite");

    // Grow the edge until the grid fits in maxCells (at most a few rounds: each one scales the
    // cell count by about maxCells / count).
    core::Vec3 const extent = hi - lo;
    double edge = minEdge;
    // Cell ids are stored as 32-bit integers.
    maxCells = std::clamp<std::size_t>(maxCells, 1, std::numeric_limits<std::uint32_t>::max() - 1);
    for (;;) {
        // Count in double and convert only once the grid is known to fit: a runaway grain can
        // make extent / edge exceed any integer type.
        std::array<double, 3> n{};
        double cells = 1.0;
        for (int d = 0; d < 3; ++d) {
            n[static_cast<std::size_t>(d)] = std::floor(extent[d] / edge) + 1.0;
            cells *= n[static_cast<std::size_t>(d)];
        }
        if (cells <= static_cast<double>(maxCells)) {
            for (std::size_t d = 0; d < 3; ++d)
                m_dims[d] = static_cast<std::int64_t>(n[d]);
            break;
        }
        edge *= std::cbrt(cells / static_cast<double>(maxCells)) * (1.0 + 1e-12);
    }
    m_origin = lo;
    m_edge = edge;
    // Rounding: x - lo in double errs by at most eps |x| per coordinate, its float by
    // 2^-24 |x - lo| <= 2^-24 |extent|; a distance of two such centres by at most
    // 2 sqrt(3) times the sum. Bounded generously: 2^-21 of the extent, 8 eps of the
    // coordinates' magnitude. The query centre of forEachOverlapWith errs less.
    double const magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    m_roundingSlack = std::ldexp(extent.maxCoeff(), -21) +
                      8.0 * std::numeric_limits<double>::epsilon() * magnitude;
    m_testSlack = m_slack + m_roundingSlack;
    // The largest radius as the floats round it up (relative 2^-24), with room to spare.
    m_perSquare = 0.5 / (2.0 * m_maxRadius * (1.0 + 1e-6) + m_testSlack);

    // Counting sort by cell (stable: members of one cell stay in input order).
    std::size_t const numCells = static_cast<std::size_t>(m_dims[0] * m_dims[1] * m_dims[2]);
    m_start.assign(numCells + 1, 0);
    m_cellOf.resize(members.size());
    for (std::size_t k = 0; k < members.size(); ++k) {
        core::Vec3 const x = positions[members[k]];
        auto const c =
            static_cast<std::uint32_t>(cellIndex(coord(x[0], 0), coord(x[1], 1), coord(x[2], 2)));
        m_cellOf[k] = c;
        ++m_start[c + 1];
    }
    for (std::size_t c = 0; c < numCells; ++c)
        m_start[c + 1] += m_start[c];
    m_member.resize(members.size());
    m_x.resize(members.size());
    m_y.resize(members.size());
    m_z.resize(members.size());
    m_radius.resize(members.size());
    // Fill using m_start[c] as the running insertion point, then shift back.
    for (std::size_t k = 0; k < members.size(); ++k) {
        std::uint32_t const slot = m_start[m_cellOf[k]]++;
        m_member[slot] = members[k];
        core::Vec3 const x = positions[members[k]] - lo;
        m_x[slot] = static_cast<float>(x.x());
        m_y[slot] = static_cast<float>(x.y());
        m_z[slot] = static_cast<float>(x.z());
        m_radius[slot] = core::floatNotBelow(radii[members[k]]);
    }
    for (std::size_t c = numCells; c > 0; --c)
        m_start[c] = m_start[c - 1];
    m_start[0] = 0;
    std::vector<std::uint32_t>().swap(m_cellOf); // scratch: 4 bytes per member
}

} // namespace regolith::particles
