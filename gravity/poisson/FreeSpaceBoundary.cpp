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
    m_near.clear();
    m_nearBucket.clear();
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
    if (!m_near.empty())
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

namespace {

constexpr std::int64_t kBucket = 2 * FreeSpaceBoundary::kLatticeRadius + 1;

/// Floor of a / kBucket.
std::int64_t bucketOf(std::int64_t a) {
    return a >= 0 ? a / kBucket : -((-a + kBucket - 1) / kBucket);
}

std::uint64_t bucketKey(std::int64_t bx, std::int64_t by, std::int64_t bz) {
    constexpr std::int64_t kBias = std::int64_t{1} << 20;
    auto const field = [](std::int64_t b) { return static_cast<std::uint64_t>(b + kBias); };
    return field(bx) | field(by) << 21U | field(bz) << 42U;
}

} // namespace

std::array<std::int64_t, 3> FreeSpaceBoundary::cellOf(core::Vec3 const& x) const {
    core::Vec3 const c = (x - m_firstCentre).cwiseQuotient(m_lattice->spacing());
    return {std::llround(c[0]), std::llround(c[1]), std::llround(c[2])};
}

void FreeSpaceBoundary::gatherNearCells(core::Comm const& comm, CellLayout const& layout,
                                        std::span<double const> mine) {
    if (!m_lattice || m_lattice->spacing() != layout.spacing())
        m_lattice.emplace(layout.spacing(), kLatticeRadius);
    m_firstCentre = layout.centre({0, 0, 0});
    auto const& N = layout.globalCells();
    std::vector<double> near;
    for (std::size_t c = 0; c + 3 < mine.size(); c += 4) {
        auto const cell = cellOf({mine[c], mine[c + 1], mine[c + 2]});
        bool close = false;
        for (std::size_t a = 0; a < 3; ++a)
            close = close || cell[a] < kLatticeRadius || cell[a] >= N[a] - kLatticeRadius;
        if (close)
            near.insert(near.end(), mine.begin() + static_cast<std::ptrdiff_t>(c),
                        mine.begin() + static_cast<std::ptrdiff_t>(c + 4));
    }
    std::vector<double> const all = comm.allGatherVarying<double>(near);
    std::vector<std::pair<std::uint64_t, NearCell>> keyed;
    keyed.reserve(all.size() / 4);
    for (std::size_t c = 0; c + 3 < all.size(); c += 4) {
        auto const cell = cellOf({all[c], all[c + 1], all[c + 2]});
        keyed.push_back({bucketKey(bucketOf(cell[0]), bucketOf(cell[1]), bucketOf(cell[2])),
                         NearCell{cell, all[c + 3]}});
    }
    // Stable: the same order on every rank, whatever the sort's implementation.
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](auto const& a, auto const& b) { return a.first < b.first; });
    for (auto const& [key, cell] : keyed) {
        m_nearBucket.push_back(key);
        m_near.push_back(cell);
    }
}

void FreeSpaceBoundary::addLatticeCorrections(std::span<core::Vec3 const> points,
                                              std::span<double> phi) const {
    constexpr std::int64_t kR = kLatticeRadius;
    LatticeGreensFunction const& lattice = *m_lattice;
    for (std::size_t i = 0; i < points.size(); ++i) {
        auto const p = cellOf(points[i]);
        double sum = 0.0;
        // The buckets of edge 2R + 1 that the box p ± R meets: at most two per axis.
        for (std::int64_t bz = bucketOf(p[2] - kR); bz <= bucketOf(p[2] + kR); ++bz)
            for (std::int64_t by = bucketOf(p[1] - kR); by <= bucketOf(p[1] + kR); ++by)
                for (std::int64_t bx = bucketOf(p[0] - kR); bx <= bucketOf(p[0] + kR); ++bx) {
                    auto const [first, last] = std::equal_range(
                        m_nearBucket.begin(), m_nearBucket.end(), bucketKey(bx, by, bz));
                    for (auto k = first; k != last; ++k) {
                        NearCell const& c =
                            m_near[static_cast<std::size_t>(k - m_nearBucket.begin())];
                        std::array<std::int64_t, 3> const n{p[0] - c.cell[0], p[1] - c.cell[1],
                                                            p[2] - c.cell[2]};
                        if (std::abs(n[0]) <= kR && std::abs(n[1]) <= kR && std::abs(n[2]) <= kR)
                            sum += c.mass * lattice.correction(n);
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
