#include "apps/spin_up/Remnants.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace regolith::apps {

namespace {

/// Union-find over indices, by size with path halving.
class DisjointSets {
public:
    explicit DisjointSets(std::size_t n)
        : m_parent(n)
        , m_size(n, 1) {
        std::iota(m_parent.begin(), m_parent.end(), std::size_t{0});
    }
    std::size_t find(std::size_t i) {
        while (m_parent[i] != i)
            i = m_parent[i] = m_parent[m_parent[i]];
        return i;
    }
    void unite(std::size_t a, std::size_t b) {
        a = find(a);
        b = find(b);
        if (a == b)
            return;
        if (m_size[a] < m_size[b])
            std::swap(a, b);
        m_parent[b] = a;
        m_size[a] += m_size[b];
    }

private:
    std::vector<std::size_t> m_parent;
    std::vector<std::size_t> m_size;
};

using Cell = std::array<std::int64_t, 3>;

struct CellHash {
    std::size_t operator()(Cell const& c) const {
        auto const u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
        return static_cast<std::size_t>(u(c[0]) * 73856093u ^ u(c[1]) * 19349663u ^
                                        u(c[2]) * 83492791u);
    }
};

} // namespace

Remnant largestRemnant(std::span<MasterRecord const> grains, double gap) {
    Remnant out;
    if (grains.empty())
        return out;
    double rMax = 0.0;
    for (MasterRecord const& g : grains)
        rMax = std::max(rMax, g.radius);
    double const cell = 2.0 * rMax + gap; // no friends farther apart than one cell
    auto const cellOf = [cell](core::Vec3 const& x) {
        return Cell{static_cast<std::int64_t>(std::floor(x.x() / cell)),
                    static_cast<std::int64_t>(std::floor(x.y() / cell)),
                    static_cast<std::int64_t>(std::floor(x.z() / cell))};
    };
    std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells;
    for (std::size_t i = 0; i < grains.size(); ++i)
        cells[cellOf(grains[i].position)].push_back(i);

    DisjointSets sets(grains.size());
    for (std::size_t i = 0; i < grains.size(); ++i) {
        Cell const c = cellOf(grains[i].position);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    auto const it = cells.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == cells.end())
                        continue;
                    for (std::size_t j : it->second) {
                        double const reach = grains[i].radius + grains[j].radius + gap;
                        if (j > i && (grains[i].position - grains[j].position).squaredNorm() <=
                                         reach * reach)
                            sets.unite(i, j);
                    }
                }
    }
    // Each cluster's mass and first moment, summed in grain order; the largest by mass, the
    // first found (lowest index, i.e. uid) on ties.
    std::vector<double> mass(grains.size(), 0.0);
    std::vector<core::Vec3> moment(grains.size(), core::Vec3::Zero());
    std::vector<std::size_t> count(grains.size(), 0);
    for (std::size_t i = 0; i < grains.size(); ++i) {
        std::size_t const root = sets.find(i);
        if (count[root] == 0)
            ++out.clusters;
        mass[root] += grains[i].mass;
        moment[root] += grains[i].mass * grains[i].position;
        ++count[root];
    }
    std::size_t best = sets.find(0);
    for (std::size_t i = 0; i < grains.size(); ++i) {
        std::size_t const root = sets.find(i);
        if (mass[root] > mass[best])
            best = root;
    }
    out.mass = mass[best];
    out.centre = moment[best] / mass[best];
    out.grains = count[best];
    return out;
}

} // namespace regolith::apps
