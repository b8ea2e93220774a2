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
        return;
    }
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
