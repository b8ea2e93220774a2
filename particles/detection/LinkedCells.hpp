#pragma once
/// Linked cells (Allen & Tildesley, "Computer Simulation of Liquids", 2nd ed., sec. 5.3.2)
/// over the centres of a set of spheres, stored as a compressed row (counting sort by cell,
/// members of a cell contiguous) with the spheres copied in cell order so that the pair loop
/// streams through memory.
///
/// The copies are single precision (16 bytes a sphere, not 32: the copy lives as long as the
/// grid, i.e. a whole Verlet list's life, for every copy of a block): centres relative to the
/// grid's origin, radii rounded up, and every overlap test widened by a bound on that rounding
/// (`roundingSlack`). So the tests can report a few extra pairs, within that bound of touching,
/// but never miss one; the callers test pairs exactly (the contact rule) or list candidates
/// (the Verlet list, whose extra pairs then cannot touch before its next rebuild).
#include "core/math/Vec3.hpp"
#include "particles/detection/CellCandidates.hpp"
#include "particles/detection/LocalPositions.hpp"
#include "particles/storage/CopyImage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace regolith::particles {

/// Axes along which the cells wrap: the grid spans [min, max) of each such axis in whole
/// cells, and a layer of cells on either side holds the members of the opposite layer
/// shifted by one period (ghost slots), so the half shell below finds every pair across
/// those faces once, with the shift of its second member. The centres must lie in
/// [min, max) on those axes.
struct CellWrap {
    std::array<bool, 3> axes{false, false, false};
    core::Vec3 min = core::Vec3::Zero();
    core::Vec3 max = core::Vec3::Zero();
    [[nodiscard]] bool any() const { return axes[0] || axes[1] || axes[2]; }
};

class LinkedCells {
public:
    using Wrap = CellWrap;

    /// Bins the spheres `members` (indices into `positions` / `radii`) by centre into cubic
    /// cells of edge >= `minEdge` [length] covering the bounding box of those centres. If that
    /// would take more than `maxCells` cells (sparse or far-flung sets), the edge grows until
    /// it does not, so memory and the empty-cell sweep stay O(members).
    /// `slack` >= 0 [length] widens every overlap test below (|x_a - x_b| < r_a + r_b + slack):
    /// callers that decide overlaps exactly in another frame use it so that rounding in this
    /// one can only add candidates, never lose one.
    /// Precondition: 2 * (max member radius) + slack <= minEdge, so that candidate members are
    /// in the same or adjacent cells; `minEdge` > 0 and finite centres.
    void build(LocalPositions const& positions, std::span<double const> radii,
               std::span<std::uint32_t const> members, double minEdge, std::size_t maxCells,
               double slack = 0.0, Wrap const& wrap = {});
    /// build() on positions used as they are.
    void build(std::span<core::Vec3 const> positions, std::span<double const> radii,
               std::span<std::uint32_t const> members, double minEdge, std::size_t maxCells,
               double slack = 0.0, Wrap const& wrap = {}) {
        build(LocalPositions(positions), radii, members, minEdge, maxCells, slack, wrap);
    }

    /// Calls `f(a, b)` (original indices) once for every unordered pair of members whose
    /// spheres overlap (|x_a - x_b| < r_a + r_b + slack), and possibly for pairs within
    /// roundingSlack() of that: same cell, then the 13 forward neighbours of the half shell,
    /// so each pair is visited at most once. Order: by cell, then slot. An `f` that takes a
    /// third argument gets `apart` [length]: where positive, the surfaces are at least that
    /// far apart (|x_a - x_b| - r_a - r_b >= apart); where they may touch, it is not
    /// positive. Without a root: d - t = (d^2 - t^2) / (d + t), and d + t < 2 (2 r_max +
    /// slack) for a pair reported. An `f` that takes a fourth gets b's shift (whole periods
    /// on the wrapped axes: b stands at x_b + shift * period from a); a grid that wraps needs
    /// such an `f`. On a wrapped axis of one or two cells a pair may come once per shift.
    template <class F>
    void forEachOverlap(F&& f) const;

    /// Calls `f(b)` for every member whose sphere overlaps the sphere (`centre`, `radius`)
    /// (within slack; possibly also within roundingSlack() more). Visits only cells
    /// intersecting the ball of radius `radius + maxMemberRadius + slack` (+ roundingSlack())
    /// about `centre`, row by row; returns the number of cells visited. On a grid that wraps
    /// `f(b, shift)` for every image of b that overlaps (b at x_b + shift * period).
    template <class F>
    std::size_t forEachOverlapWith(core::Vec3 const& centre, double radius, F&& f) const;

    [[nodiscard]] double edge() const { return m_edge; }
    /// How much farther apart than touching (+ slack) a reported pair may be [length].
    [[nodiscard]] double roundingSlack() const { return m_roundingSlack; }
    [[nodiscard]] std::array<std::int64_t, 3> dims() const { return m_dims; }
    [[nodiscard]] std::size_t numCells() const { return m_start.empty() ? 0 : m_start.size() - 1; }
    [[nodiscard]] std::size_t numMembers() const { return m_members; }
    /// The members in cell order (cell by cell, z slowest, x fastest); with ghost slots
    /// (a grid that wraps) a member may appear more than once.
    [[nodiscard]] std::span<std::uint32_t const> membersInCellOrder() const { return m_member; }
    /// Heap bytes held.
    [[nodiscard]] std::size_t bytes() const {
        return m_start.capacity() * sizeof(std::uint32_t) +
               m_member.capacity() * sizeof(std::uint32_t) + 4 * m_x.capacity() * sizeof(float) +
               m_shift.capacity() * sizeof(CopyImage);
    }

private:
    /// The spheres in slot order, as lanes: centres relative to m_origin rounded to nearest,
    /// radii rounded up.
    [[nodiscard]] cells_detail::SphereLanes lanes() const {
        return {m_x.data(), m_y.data(), m_z.data(), m_radius.data()};
    }
    /// forEachOverlapWith for one image of the query, over the real cells.
    template <class F>
    std::size_t overlapsOfOneImage(core::Vec3 const& centre, double radius, double reach,
                                   F&& f) const;
    /// f(member of slot s, member of slot t), with forEachOverlap's `apart` if f takes it.
    template <class F>
    void report(F& f, std::uint32_t s, std::uint32_t t, double d2) const {
        if constexpr (std::is_invocable_v<F&, std::uint32_t, std::uint32_t, double, CopyImage>) {
            double const touch = double{m_radius[s]} + double{m_radius[t]};
            CopyImage const shift = m_shift.empty() ? kNoImage : m_shift[t];
            f(m_member[s], m_member[t], (d2 - touch * touch) * m_perSquare - m_roundingSlack,
              shift);
        } else if constexpr (std::is_invocable_v<F&, std::uint32_t, std::uint32_t, double>) {
            double const touch = double{m_radius[s]} + double{m_radius[t]};
            // The float centres are within the rounding slack of the true distance; the float
            // radii are rounded up.
            f(m_member[s], m_member[t], (d2 - touch * touch) * m_perSquare - m_roundingSlack);
        } else {
            (void)d2;
            f(m_member[s], m_member[t]);
        }
    }
    /// Cell coordinate of `x` along `axis`, clamped to the real cells (clamped in floating
    /// point, so far-away query points cannot overflow the integer conversion).
    [[nodiscard]] std::int64_t coord(double x, int axis) const {
        auto const u = static_cast<std::size_t>(axis);
        double const c = std::floor((x - m_origin[axis]) / m_edges[axis]);
        if (!(c >= static_cast<double>(m_real[u][0])))
            return m_real[u][0];
        return c > static_cast<double>(m_real[u][1]) ? m_real[u][1] : static_cast<std::int64_t>(c);
    }
    [[nodiscard]] std::size_t cellIndex(std::int64_t x, std::int64_t y, std::int64_t z) const {
        return static_cast<std::size_t>((z * m_dims[1] + y) * m_dims[0] + x);
    }

    core::Vec3 m_origin = core::Vec3::Zero();
    double m_edge = 1.0;                            ///< the cells' edge on the axes that do not wrap
    core::Vec3 m_edges = core::Vec3::Ones();        ///< per axis (a wrapped one: period / cells)
    core::Vec3 m_period = core::Vec3::Zero();       ///< on the wrapped axes, else 0
    std::array<std::array<std::int64_t, 2>, 3> m_real{}; ///< first and last real cell per axis
    std::size_t m_members = 0;                       ///< members (slots less the ghosts)
    double m_maxRadius = 0.0;
    double m_slack = 0.0;
    double m_roundingSlack = 0.0; ///< bound on the float rounding of two centres' distance
    double m_testSlack = 0.0;     ///< m_slack + m_roundingSlack
    double m_perSquare = 0.0;     ///< 1 / (2 (2 r_max + m_testSlack)), r_max as a float rounds it
    std::array<std::int64_t, 3> m_dims{0, 0, 0};
    std::vector<std::uint32_t> m_start;  ///< cell c holds slots [m_start[c], m_start[c+1])
    std::vector<std::uint32_t> m_member; ///< original index of each slot (< 2^32 copies)
    std::vector<float> m_x, m_y, m_z;    ///< centre of each slot (lanes())
    std::vector<float> m_radius;         ///< radius of each slot, rounded up
    std::vector<CopyImage> m_shift;      ///< per slot where the grid wraps (ghosts: non-zero)
};

// ---- implementation of the templates ------------------------------------------------------

template <class F>
void LinkedCells::forEachOverlap(F&& f) const {
    auto const nx = m_dims[0], ny = m_dims[1], nz = m_dims[2];
    // The half shell of 13 forward neighbours, grouped into 5 slot ranges: cell x+1 of the
    // same row, and the cells x-1..x+1 of the rows (dy, dz) = (1, 0), (-1, 1), (0, 1), (1, 1),
    // which are consecutive in memory, so each row is one contiguous range of slots. A cell's
    // candidates are tested range by range in lanes (CellCandidates.hpp; whether two grains of
    // a packing are within reach is a coin toss for the branch predictor), then reported.
    static constexpr std::int64_t kRows[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    cells_detail::SphereLanes const spheres = lanes();
    cells_detail::CellScratch scratch;
    std::vector<cells_detail::SlotPair> hits;
    std::array<cells_detail::SlotRange, 5> forward{};
    for (std::int64_t z = m_real[2][0]; z <= m_real[2][1]; ++z)
        for (std::int64_t y = m_real[1][0]; y <= m_real[1][1]; ++y)
            for (std::int64_t x = m_real[0][0]; x <= m_real[0][1]; ++x) {
                std::size_t const c = cellIndex(x, y, z);
                std::uint32_t const begin = m_start[c], end = m_start[c + 1];
                if (begin == end)
                    continue;
                std::size_t ranges = 0;
                if (x + 1 < nx)
                    forward[ranges++] = {end, m_start[c + 2]};
                std::int64_t const x0 = x > 0 ? x - 1 : 0, x1 = x + 1 < nx ? x + 1 : x;
                for (auto const& row : kRows) {
                    std::int64_t const oy = y + row[0], oz = z + row[1];
                    if (oy < 0 || oy >= ny || oz >= nz)
                        continue;
                    forward[ranges++] = {m_start[cellIndex(x0, oy, oz)],
                                         m_start[cellIndex(x1, oy, oz) + 1]};
                }
                hits.clear();
                cells_detail::appendCellOverlaps(spheres, {begin, end},
                                                 std::span(forward.data(), ranges), m_testSlack,
                                                 scratch, hits);
                for (cells_detail::SlotPair const& h : hits)
                    report(f, h.s, h.t, h.d2);
            }
}

template <class F>
std::size_t LinkedCells::forEachOverlapWith(core::Vec3 const& centre, double radius, F&& f) const {
    if (m_member.empty())
        return 0;
    // A member centre beyond this cannot touch.
    double const reach = radius + m_maxRadius + m_testSlack;
    // On a wrapped axis the query's images whose ball meets the real cells: the query at
    // centre - k * period finds the members b standing at x_b + k * period from it.
    std::array<std::int64_t, 3> kLo{0, 0, 0}, kHi{0, 0, 0};
    for (int d = 0; d < 3; ++d) {
        auto const u = static_cast<std::size_t>(d);
        double const begin =
            m_origin[d] + static_cast<double>(m_real[u][0]) * m_edges[d];
        double const end = m_origin[d] + static_cast<double>(m_real[u][1] + 1) * m_edges[d];
        if (m_period[d] > 0.0) {
            kLo[u] = static_cast<std::int64_t>(std::ceil((centre[d] - reach - end) / m_period[d]));
            kHi[u] =
                static_cast<std::int64_t>(std::floor((centre[d] + reach - begin) / m_period[d]));
        } else if (centre[d] + reach < begin || centre[d] - reach > end) {
            return 0; // the ball misses the grid
        }
    }
    std::size_t visited = 0;
    for (std::int64_t kz = kLo[2]; kz <= kHi[2]; ++kz)
        for (std::int64_t ky = kLo[1]; ky <= kHi[1]; ++ky)
            for (std::int64_t kx = kLo[0]; kx <= kHi[0]; ++kx) {
                CopyImage const shift{static_cast<std::int8_t>(kx), static_cast<std::int8_t>(ky),
                                      static_cast<std::int8_t>(kz)};
                core::Vec3 const at =
                    centre - core::Vec3(static_cast<double>(kx) * m_period.x(),
                                        static_cast<double>(ky) * m_period.y(),
                                        static_cast<double>(kz) * m_period.z());
                visited += overlapsOfOneImage(at, radius, reach, [&](std::uint32_t b) {
                    if constexpr (std::is_invocable_v<F&, std::uint32_t, CopyImage>)
                        f(b, shift);
                    else
                        f(b);
                });
            }
    return visited;
}

template <class F>
std::size_t LinkedCells::overlapsOfOneImage(core::Vec3 const& centre, double radius, double reach,
                                            F&& f) const {
    auto lo = [&](int axis) { return coord(centre[axis] - reach, axis); };
    auto hi = [&](int axis) { return coord(centre[axis] + reach, axis); };
    // Distance from `v` to the slab [o + c h, o + (c + 1) h] along `axis` (0 inside).
    auto gap = [&](std::int64_t c, int axis) {
        double const a = m_origin[axis] + static_cast<double>(c) * m_edges[axis];
        double const v = centre[axis];
        return v < a ? a - v : (v > a + m_edges[axis] ? v - a - m_edges[axis] : 0.0);
    };
    std::size_t visited = 0;
    core::Vec3 const rel = centre - m_origin; // the frame of the stored centres
    std::int64_t const z0 = lo(2), z1 = hi(2), y0 = lo(1), y1 = hi(1);
    for (std::int64_t z = z0; z <= z1; ++z) {
        double const gz = gap(z, 2);
        for (std::int64_t y = y0; y <= y1; ++y) {
            double const gy = gap(y, 1);
            double const rest = reach * reach - gz * gz - gy * gy;
            if (rest < 0.0)
                continue; // this row of cells misses the ball
            double const w = std::sqrt(rest);
            std::int64_t const x0 = coord(centre[0] - w, 0), x1 = coord(centre[0] + w, 0);
            visited += static_cast<std::size_t>(x1 - x0 + 1);
            std::uint32_t const begin = m_start[cellIndex(x0, y, z)];
            std::uint32_t const end = m_start[cellIndex(x1, y, z) + 1];
            // Cells of one row are consecutive, so the row is one contiguous slot range (the
            // real cells only: coord clamps to them, and no ghost lies between two).
            for (std::uint32_t t = begin; t < end; ++t) {
                double const dx = double{m_x[t]} - rel.x(), dy = double{m_y[t]} - rel.y(),
                             dz = double{m_z[t]} - rel.z();
                double const touch = radius + double{m_radius[t]} + m_testSlack;
                if (dx * dx + dy * dy + dz * dz < touch * touch)
                    f(m_member[t]);
            }
        }
    }
    return visited;
}

} // namespace regolith::particles
