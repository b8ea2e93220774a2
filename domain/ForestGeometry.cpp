#include "domain/ForestGeometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace regolith::domain {

ForestGeometry::ForestGeometry(core::AABB const& domain, std::array<int, 3> rootBlocks,
                               std::array<bool, 3> periodic, int maxLevel)
    : m_domain(domain)
    , m_rootBlocks(rootBlocks)
    , m_periodic(periodic)
    , m_maxLevel(maxLevel) {
    for (int a = 0; a < 3; ++a)
        m_latticeSize[a] = LatticeIndex{rootBlocks[a]} << maxLevel;
}

std::uint64_t ForestGeometry::rootCount() const {
    return static_cast<std::uint64_t>(m_rootBlocks[0]) *
           static_cast<std::uint64_t>(m_rootBlocks[1]) *
           static_cast<std::uint64_t>(m_rootBlocks[2]);
}

double ForestGeometry::coordinate(int axis, LatticeIndex i) const {
    // i / n is correctly rounded, so a plane shared by root blocks has the same coordinate
    // whatever maxLevel is; lerp is exact at both ends and monotone.
    double const t = static_cast<double>(i) / static_cast<double>(m_latticeSize[axis]);
    return std::lerp(m_domain.min[axis], m_domain.max[axis], t);
}

std::uint64_t ForestGeometry::rootIndex(LatticeCell const& rootCoord) const {
    auto const nx = static_cast<std::uint64_t>(m_rootBlocks[0]);
    auto const ny = static_cast<std::uint64_t>(m_rootBlocks[1]);
    return static_cast<std::uint64_t>(rootCoord[0]) +
           nx * (static_cast<std::uint64_t>(rootCoord[1]) +
                 ny * static_cast<std::uint64_t>(rootCoord[2]));
}

LatticeCell ForestGeometry::rootCoord(std::uint64_t rootIndex) const {
    auto const nx = static_cast<std::uint64_t>(m_rootBlocks[0]);
    auto const ny = static_cast<std::uint64_t>(m_rootBlocks[1]);
    return {static_cast<LatticeIndex>(rootIndex % nx),
            static_cast<LatticeIndex>((rootIndex / nx) % ny),
            static_cast<LatticeIndex>(rootIndex / (nx * ny))};
}

LatticeBox ForestGeometry::latticeBox(BlockId id) const {
    LatticeCell const root = rootCoord(id.rootIndex());
    LatticeIndex size = rootSize();
    LatticeBox b;
    for (int a = 0; a < 3; ++a)
        b.lo[a] = root[a] * size;
    int const level = id.level();
    for (int l = 1; l <= level; ++l) {
        size /= 2;
        int const k = id.octantAt(l);
        for (int a = 0; a < 3; ++a)
            b.lo[a] += ((k >> a) & 1) * size;
    }
    for (int a = 0; a < 3; ++a)
        b.hi[a] = b.lo[a] + size;
    return b;
}

core::AABB ForestGeometry::box(LatticeBox const& b) const {
    core::AABB out;
    for (int a = 0; a < 3; ++a) {
        out.min[a] = coordinate(a, b.lo[a]);
        out.max[a] = coordinate(a, b.hi[a]);
    }
    return out;
}

BlockId ForestGeometry::blockAt(LatticeCell const& cell, int level) const {
    LatticeIndex const s = rootSize();
    LatticeCell const root{cell[0] / s, cell[1] / s, cell[2] / s};
    BlockId id = BlockId::root(rootIndex(root));
    for (int l = 1; l <= level; ++l) {
        int const bit = m_maxLevel - l;
        int k = 0;
        for (int a = 0; a < 3; ++a)
            k |= static_cast<int>(((cell[a] - root[a] * s) >> bit) & 1) << a;
        id = id.child(k);
    }
    return id;
}

core::Vec3 ForestGeometry::shift(PeriodicImage const& image) const {
    core::Vec3 s = core::Vec3::Zero();
    core::Vec3 const extent = m_domain.extent();
    for (int a = 0; a < 3; ++a)
        if (image[a] != 0)
            s[a] = -static_cast<double>(image[a]) * extent[a];
    return s;
}

std::pair<int, double> wrapOnAxis(double lo, double hi, double x) {
    if (x >= lo && x < hi)
        return {0, x};
    double const extent = hi - lo;
    // Images so far away that the period count leaves int are not part of any neighbourhood;
    // clamping keeps the arithmetic defined (the wrapped value is then only approximate).
    double const periods = std::clamp(std::floor((x - lo) / extent), -1e9, 1e9);
    auto o = static_cast<int>(periods);
    // Decide the image with the same boundaries min + o * extent that shifted boxes use; the
    // floor above is at most one off, so two corrections in each direction are plenty.
    for (int it = 0; it < 2 && x < lo + static_cast<double>(o) * extent; ++it)
        --o;
    for (int it = 0; it < 2 && x >= lo + static_cast<double>(o + 1) * extent; ++it)
        ++o;
    double w = x - static_cast<double>(o) * extent;
    if (w < lo)
        w = lo;
    if (w >= hi)
        w = std::nextafter(hi, lo);
    return {o, w};
}

core::Vec3 ForestGeometry::wrap(core::Vec3 const& p) const {
    core::Vec3 out = p;
    for (int a = 0; a < 3; ++a)
        if (m_periodic[a] && std::isfinite(p[a]))
            out[a] = wrapAxis(a, p[a]).second;
    return out;
}

bool ForestGeometry::insideDomain(core::Vec3 const& p) const {
    for (int a = 0; a < 3; ++a) {
        if (m_periodic[a] ? !std::isfinite(p[a])
                          : !(p[a] >= m_domain.min[a] && p[a] < m_domain.max[a]))
            return false;
    }
    return true;
}

LatticeIndex ForestGeometry::cellOnAxis(int axis, double x) const {
    LatticeIndex const n = m_latticeSize[axis];
    double const lo = m_domain.min[axis];
    double const t = (x - lo) / (m_domain.max[axis] - lo) * static_cast<double>(n);
    auto i = static_cast<LatticeIndex>(std::clamp(std::floor(t), 0.0, static_cast<double>(n - 1)));
    // The estimate can be one off near a plane; settle it against the exact plane coordinates.
    while (i > 0 && x < coordinate(axis, i))
        --i;
    while (i < n - 1 && x >= coordinate(axis, i + 1))
        ++i;
    return i;
}

std::optional<ForestGeometry::Location> ForestGeometry::locate(core::Vec3 const& p) const {
    Location loc{{0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(p[a]))
            return std::nullopt;
        double x = p[a];
        if (m_periodic[a]) {
            auto const [o, w] = wrapAxis(a, x);
            loc.image[a] = o;
            x = w;
        } else if (!(x >= m_domain.min[a] && x < m_domain.max[a])) {
            return std::nullopt;
        }
        loc.cell[a] = cellOnAxis(a, x);
    }
    return loc;
}

} // namespace regolith::domain
