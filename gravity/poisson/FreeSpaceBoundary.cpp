#include "gravity/poisson/FreeSpaceBoundary.hpp"

#include "core/Error.hpp"
#include "gravity/tree/InteractionList.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace regolith::gravity {

void FreeSpaceBoundary::update(core::Comm const& comm, CellField const& density, double G) {
    m_G = G;
    std::vector<double> const mine = occupiedCells(density);
    m_moments = massMoments(comm, mine, density.layout().forest().domain().center());
    m_useTree = m_moments.mass > 0.0 && m_moments.occupiedCells <= kGatherCells;
    for (auto& slab : m_slab)
        slab.clear();
    if (m_kernel == BoundaryKernel::Lattice && m_moments.mass > 0.0)
        gatherNearCells(comm, density.layout(), mine);
    m_tree = tree::Octree();
    if (!m_useTree)
        return;
    // Every rank's occupied cells, on every rank.
    std::vector<double> const all = comm.allGatherVarying<double>(mine);
    std::size_t const n = all.size() / 4;
    std::vector<double> x(n), y(n), z(n), m(n);
    for (std::size_t c = 0; c < n; ++c) {
        x[c] = all[4 * c];
        y[c] = all[4 * c + 1];
        z[c] = all[4 * c + 2];
        m[c] = all[4 * c + 3];
    }
    tree::OctreeBuildOptions options;
    options.theta = kTheta;
    options.leafSize = 8;
    m_tree = tree::Octree::build(PointMasses{x, y, z, m}, options);
}

void FreeSpaceBoundary::evaluate(std::span<core::Vec3 const> points, std::span<double> phi) const {
    if (phi.size() != points.size())
        throw core::Error("FreeSpaceBoundary::evaluate: output size does not match the points");
    if (!m_useTree) {
        for (std::size_t i = 0; i < points.size(); ++i)
            phi[i] = m_moments.mass > 0.0 ? multipolePotential(m_moments, m_G, points[i]) : 0.0;
    } else {
        evaluateTree(points, phi);
    }
    if (m_lattice &&
        std::any_of(m_slab.begin(), m_slab.end(), [](auto const& s) { return !s.empty(); }))
        addLatticeCorrections(points, phi);
}

void FreeSpaceBoundary::evaluateTree(std::span<core::Vec3 const> points,
                                     std::span<double> phi) const {
    tree::InteractionList list;
    std::vector<std::int32_t> stack;
    std::array<std::array<double, kGroupSize>, 3> t{};
    std::array<double, kGroupSize> ax{};
    std::array<double, kGroupSize> ay{};
    std::array<double, kGroupSize> az{};
    std::array<double, kGroupSize> p{};
    for (std::size_t begin = 0; begin < points.size(); begin += kGroupSize) {
        std::size_t const count = std::min(kGroupSize, points.size() - begin);
        core::AABB group{points[begin], points[begin]};
        for (std::size_t i = 0; i < count; ++i) {
            core::Vec3 const& x = points[begin + i];
            group.min = group.min.cwiseMin(x);
            group.max = group.max.cwiseMax(x);
            for (std::size_t a = 0; a < 3; ++a)
                t[a][i] = x[static_cast<Eigen::Index>(a)];
            ax[i] = ay[i] = az[i] = p[i] = 0.0;
        }
        list.clear();
        tree::collectInteractions(m_tree.view(), group, true, list, stack);
        list.evaluate(t[0].data(), t[1].data(), t[2].data(), count, m_G, 0.0, ax.data(), ay.data(),
                      az.data(), p.data());
        std::copy_n(p.begin(), count, phi.begin() + static_cast<std::ptrdiff_t>(begin));
    }
}

std::array<std::int64_t, 3> FreeSpaceBoundary::cellOf(core::Vec3 const& x) const {
    core::Vec3 const c = (x - m_firstCentre).cwiseQuotient(m_lattice->spacing());
    return {std::llround(c[0]), std::llround(c[1]), std::llround(c[2])};
}

void FreeSpaceBoundary::gatherNearCells(core::Comm const& comm, CellLayout const& layout,
                                        std::span<double const> mine) {
    if (!m_lattice || m_lattice->spacing() != layout.spacing())
        m_lattice.emplace(layout.spacing(), kLatticeRadius);
    m_firstCentre = layout.centre({0, 0, 0});
    m_cells = layout.globalCells();
    auto const depth = [&](std::array<std::int64_t, 3> const& cell, std::size_t f) {
        std::size_t const a = f / 2;
        return f % 2 == 0 ? cell[a] : m_cells[a] - 1 - cell[a];
    };
    std::vector<double> near;
    for (std::size_t c = 0; c + 3 < mine.size(); c += 4) {
        auto const cell = cellOf({mine[c], mine[c + 1], mine[c + 2]});
        for (std::size_t f = 0; f < 6; ++f)
            if (depth(cell, f) < kLatticeRadius) {
                near.insert(near.end(), mine.begin() + static_cast<std::ptrdiff_t>(c),
                            mine.begin() + static_cast<std::ptrdiff_t>(c + 4));
                break;
            }
    }
    std::vector<double> const all = comm.allGatherVarying<double>(near);
    for (std::size_t c = 0; c + 3 < all.size(); c += 4) {
        auto const cell = cellOf({all[c], all[c + 1], all[c + 2]});
        for (std::size_t f = 0; f < 6; ++f) {
            std::int64_t const d = depth(cell, f);
            if (d >= kLatticeRadius)
                continue;
            std::size_t const a = f / 2, b = (a + 1) % 3, e = (a + 2) % 3;
            std::vector<double>& slab = m_slab[f];
            if (slab.empty())
                slab.assign(static_cast<std::size_t>(kLatticeRadius * m_cells[b] * m_cells[e]),
                            0.0);
            slab[static_cast<std::size_t>((d * m_cells[b] + cell[b]) * m_cells[e] + cell[e])] +=
                all[c + 3];
        }
    }
}

void FreeSpaceBoundary::addLatticeCorrections(std::span<core::Vec3 const> points,
                                              std::span<double> phi) const {
    constexpr std::int64_t kR = kLatticeRadius;
    LatticeGreensFunction const& lattice = *m_lattice;
    for (std::size_t i = 0; i < points.size(); ++i) {
        auto const p = cellOf(points[i]);
        // The face beyond which p lies (the first axis it is outside on): its slab holds
        // every occupied cell within kR of p on every axis.
        std::size_t f = 6;
        std::int64_t beyond = 0; // cells from p to the face's first layer (>= 1)
        for (std::size_t a = 0; a < 3 && f == 6; ++a) {
            if (p[a] < 0) {
                f = 2 * a;
                beyond = -p[a];
            } else if (p[a] >= m_cells[a]) {
                f = 2 * a + 1;
                beyond = p[a] - m_cells[a] + 1;
            }
        }
        if (f == 6 || m_slab[f].empty())
            continue;
        std::size_t const a = f / 2, b = (a + 1) % 3, e = (a + 2) % 3;
        std::vector<double> const& slab = m_slab[f];
        std::int64_t const b0 = std::max<std::int64_t>(0, p[b] - kR);
        std::int64_t const b1 = std::min(m_cells[b] - 1, p[b] + kR);
        std::int64_t const e0 = std::max<std::int64_t>(0, p[e] - kR);
        std::int64_t const e1 = std::min(m_cells[e] - 1, p[e] + kR);
        double sum = 0.0;
        std::array<std::int64_t, 3> n{};
        for (std::int64_t d = 0; d + beyond <= kR; ++d) {
            n[a] = d + beyond;
            for (std::int64_t cb = b0; cb <= b1; ++cb) {
                n[b] = p[b] - cb;
                double const* row =
                    &slab[static_cast<std::size_t>((d * m_cells[b] + cb) * m_cells[e])];
                for (std::int64_t ce = e0; ce <= e1; ++ce)
                    if (row[ce] != 0.0) {
                        n[e] = p[e] - ce;
                        sum += row[ce] * lattice.correction(n);
                    }
            }
        }
        phi[i] -= m_G * sum;
    }
}

namespace {

/// Spreads the low 21 bits of v to every third bit.
std::uint64_t spreadBits(std::uint64_t v) {
    v &= 0x1fffffULL;
    v = (v | v << 32U) & 0x1f00000000ffffULL;
    v = (v | v << 16U) & 0x1f0000ff0000ffULL;
    v = (v | v << 8U) & 0x100f00f00f00f00fULL;
    v = (v | v << 4U) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2U) & 0x1249249249249249ULL;
    return v;
}

} // namespace

std::vector<std::size_t> FreeSpaceBoundary::coherentOrder(std::span<GlobalCell const> cells) {
    std::vector<std::uint64_t> key(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) {
        auto const code = [&](std::size_t a) {
            return spreadBits(static_cast<std::uint64_t>(cells[i][a] + 8));
        };
        key[i] = code(0) | code(1) << 1U | code(2) << 2U;
    }
    std::vector<std::size_t> order(cells.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    return order;
}

} // namespace regolith::gravity
