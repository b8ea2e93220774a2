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
                        std::size_t maxCells, double slack, Wrap const& wrap) {
    m_member.clear();
    m_x.clear();
    m_y.clear();
    m_z.clear();
    m_radius.clear();
    m_start.clear();
    m_shift.clear();
    m_maxRadius = 0.0;
    m_slack = slack;
    m_roundingSlack = 0.0;
    m_testSlack = slack;
    m_dims = {0, 0, 0};
    m_real = {};
    m_members = 0;
    m_period = core::Vec3::Zero();
    if (members.empty())
        return;
    if (members.size() >= std::numeric_limits<std::uint32_t>::max() / 8)
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
    for (int d = 0; d < 3; ++d)
        if (wrap.axes[static_cast<std::size_t>(d)]) {
            if (!(wrap.max[d] > wrap.min[d]) || !std::isfinite(wrap.max[d] - wrap.min[d]))
                throw core::Error("LinkedCells: a wrapped axis needs a finite period");
            if (!(lo[d] >= wrap.min[d] && hi[d] < wrap.max[d]))
                throw core::Error("LinkedCells: a centre lies outside the period of a wrapped "
                                  "axis");
            m_period[d] = wrap.max[d] - wrap.min[d];
        }

    // Grow the edge until the grid fits in maxCells (at most a few rounds: each one scales the
    // cell count by about maxCells / count). A wrapped axis holds whole cells of at least the
    // edge across its period, and a ghost layer on either side.
    core::Vec3 const extent = hi - lo;
    double edge = minEdge;
    // Cell ids are stored as 32-bit integers.
    maxCells = std::clamp<std::size_t>(maxCells, 1, std::numeric_limits<std::uint32_t>::max() - 1);
    // Never fewer than the grid can have: one real cell and two ghost layers on a wrapped axis.
    std::size_t fewest = 1;
    for (int d = 0; d < 3; ++d)
        fewest *= m_period[d] > 0.0 ? 3 : 1;
    maxCells = std::max(maxCells, fewest);
    std::array<double, 3> n{};
    for (;;) {
        // Count in double and convert only once the grid is known to fit: a runaway grain can
        // make extent / edge exceed any integer type.
        double cells = 1.0;
        for (int d = 0; d < 3; ++d) {
            auto const u = static_cast<std::size_t>(d);
            n[u] = m_period[d] > 0.0 ? std::max(1.0, std::floor(m_period[d] / edge)) + 2.0
                                     : std::floor(extent[d] / edge) + 1.0;
            cells *= n[u];
        }
        if (cells <= static_cast<double>(maxCells))
            break;
        edge *= std::cbrt(cells / static_cast<double>(maxCells)) * (1.0 + 1e-12);
    }
    m_edge = edge;
    for (int d = 0; d < 3; ++d) {
        auto const u = static_cast<std::size_t>(d);
        m_dims[u] = static_cast<std::int64_t>(n[u]);
        if (m_period[d] > 0.0) {
            m_edges[d] = m_period[d] / (n[u] - 2.0);
            m_origin[d] = wrap.min[d] - m_edges[d];
            m_real[u] = {1, m_dims[u] - 2};
        } else {
            m_edges[d] = edge;
            m_origin[d] = lo[d];
            m_real[u] = {0, m_dims[u] - 1};
        }
    }
    // Rounding: x - origin in double errs by at most eps |x| per coordinate, its float by
    // 2^-24 |x - origin| <= 2^-24 |grid|; a distance of two such centres by at most
    // 2 sqrt(3) times the sum. Bounded generously: 2^-21 of the grid's extent, 8 eps of the
    // coordinates' magnitude (a ghost's shifted by a period). The query centre of
    // forEachOverlapWith errs less.
    double gridExtent = 0.0;
    for (int d = 0; d < 3; ++d)
        gridExtent = std::max(gridExtent, static_cast<double>(m_dims[static_cast<std::size_t>(d)]) *
                                              m_edges[d]);
    double const magnitude =
        std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) + m_period.maxCoeff();
    m_roundingSlack =
        std::ldexp(gridExtent, -21) + 8.0 * std::numeric_limits<double>::epsilon() * magnitude;
    m_testSlack = m_slack + m_roundingSlack;
    // The largest radius as the floats round it up (relative 2^-24), with room to spare.
    m_perSquare = 0.5 / (2.0 * m_maxRadius * (1.0 + 1e-6) + m_testSlack);

    // The slots: every member in its cell, and where the grid wraps its ghosts, the member
    // shifted by a period into the layer beyond the opposite face.
    struct Slot {
        std::uint32_t member;
        std::uint32_t cell;
        CopyImage shift;
    };
    std::vector<Slot> slots;
    slots.reserve(members.size());
    bool const wraps = m_period.maxCoeff() > 0.0;
    for (std::uint32_t k : members) {
        core::Vec3 const x = positions[k];
        std::array<std::int64_t, 3> const c{coord(x[0], 0), coord(x[1], 1), coord(x[2], 2)};
        slots.push_back({k, static_cast<std::uint32_t>(cellIndex(c[0], c[1], c[2])), kNoImage});
        if (!wraps)
            continue;
        // Per axis the shifts this member's cell has ghosts for (0 always).
        std::array<std::array<std::int8_t, 3>, 3> options{};
        std::array<std::size_t, 3> count{1, 1, 1};
        for (std::size_t u = 0; u < 3; ++u) {
            options[u][0] = 0;
            if (m_period[static_cast<int>(u)] > 0.0) {
                if (c[u] == m_real[u][1])
                    options[u][count[u]++] = -1;
                if (c[u] == m_real[u][0])
                    options[u][count[u]++] = 1;
            }
        }
        for (std::size_t i = 0; i < count[0]; ++i)
            for (std::size_t j = 0; j < count[1]; ++j)
                for (std::size_t l = 0; l < count[2]; ++l) {
                    CopyImage const s{options[0][i], options[1][j], options[2][l]};
                    if (isZero(s))
                        continue;
                    auto const n0 = m_real[0][1], n1 = m_real[1][1], n2 = m_real[2][1];
                    slots.push_back({k,
                                     static_cast<std::uint32_t>(cellIndex(
                                         c[0] + s[0] * n0, c[1] + s[1] * n1, c[2] + s[2] * n2)),
                                     s});
                }
    }
    m_members = members.size();

    // Counting sort by cell (stable: members of one cell stay in input order).
    std::size_t const numCells = static_cast<std::size_t>(m_dims[0] * m_dims[1] * m_dims[2]);
    m_start.assign(numCells + 1, 0);
    for (Slot const& slot : slots)
        ++m_start[slot.cell + 1];
    for (std::size_t c = 0; c < numCells; ++c)
        m_start[c + 1] += m_start[c];
    std::size_t const total = slots.size();
    m_member.resize(total);
    m_x.resize(total);
    m_y.resize(total);
    m_z.resize(total);
    m_radius.resize(total);
    if (wraps)
        m_shift.resize(total);
    // Fill using m_start[c] as the running insertion point, then shift back.
    for (Slot const& slot : slots) {
        std::uint32_t const at = m_start[slot.cell]++;
        m_member[at] = slot.member;
        core::Vec3 const x = localPosition(positions[slot.member], slot.shift, m_period) - m_origin;
        m_x[at] = static_cast<float>(x.x());
        m_y[at] = static_cast<float>(x.y());
        m_z[at] = static_cast<float>(x.z());
        m_radius[at] = core::floatNotBelow(radii[slot.member]);
        if (wraps)
            m_shift[at] = slot.shift;
    }
    for (std::size_t c = numCells; c > 0; --c)
        m_start[c] = m_start[c - 1];
    m_start[0] = 0;
}

} // namespace regolith::particles
