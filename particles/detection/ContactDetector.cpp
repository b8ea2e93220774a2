#include "particles/detection/ContactDetector.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace regolith::particles {

namespace {

using Index = ParticleStorage::Index;

/// Appends the contact of overlapping spheres a and b if its point is in `region`.
void emitPair(ParticleStorage const& ps, Index a, Index b, core::AABB const& region,
              std::vector<Contact>& out) {
    if (ps.flags(a).isFixed() && ps.flags(b).isFixed())
        return;
    Index const i = ps.uid(a) < ps.uid(b) ? a : b;
    Index const j = i == a ? b : a;
    core::Vec3 const d = ps.position(j) - ps.position(i);
    double const dist = d.norm();
    // Coincident centres have no direction; any unit normal is as good, this one is fixed.
    core::Vec3 const n = dist > 0.0 ? core::Vec3(d / dist) : core::Vec3::UnitZ();
    double const delta = ps.radius(i) + ps.radius(j) - dist;
    core::Vec3 const p = ps.position(i) + (ps.radius(i) - 0.5 * delta) * n;
    if (region.contains(p))
        out.push_back(Contact{i, j, p, n, delta});
}

} // namespace

core::AABB everywhere() {
    double const inf = std::numeric_limits<double>::infinity();
    return core::AABB{core::Vec3::Constant(-inf), core::Vec3::Constant(inf)};
}

ContactDetector::ContactDetector(DetectorConfig config)
    : m_config(config) {
    if (!(m_config.skin >= 0.0) || !(m_config.largeRadius >= 0.0) || !(m_config.largeFactor >= 1.0))
        throw core::InputError("contact detection: skin and large_radius must be >= 0 and "
                               "large_factor >= 1");
}

double ContactDetector::largeThreshold(ParticleStorage const& ps) {
    if (m_config.largeRadius > 0.0)
        return m_config.largeRadius;
    // Median by selection, O(N).
    m_scratch.assign(ps.radii().begin(), ps.radii().end());
    auto mid = m_scratch.begin() + static_cast<std::ptrdiff_t>(m_scratch.size() / 2);
    std::nth_element(m_scratch.begin(), mid, m_scratch.end());
    return m_config.largeFactor * *mid;
}

void ContactDetector::detect(ParticleStorage const& ps, WallList const& walls,
                             core::AABB const& region, ContactList& out) {
    out.clear();
    m_stats = DetectorStats{};
    m_small.clear();
    m_large.clear();
    if (ps.empty()) {
        m_cells.build({}, {}, {}, 1.0, 1); // forget the last grid (spatialOrder)
        return;
    }

    double const cut = largeThreshold(ps);
    double rSmallMax = 0.0;
    for (Index k = 0, n = ps.size(); k < n; ++k) {
        double const r = ps.radius(k);
        if (r > cut) {
            m_large.push_back(k);
        } else {
            m_small.push_back(k);
            rSmallMax = std::max(rSmallMax, r);
        }
    }
    m_stats.largeThreshold = cut;
    m_stats.smallSpheres = m_small.size();
    m_stats.largeSpheres = m_large.size();

    double edge = 2.0 * rSmallMax + m_config.skin;
    if (!(edge > 0.0)) // only zero radii: any positive edge is right
        edge = 1.0;
    m_cells.build(ps.positions(), ps.radii(), m_small, edge,
                  m_config.maxCellsPerSphere * std::max<std::size_t>(m_small.size(), 1));
    m_stats.cellEdge = m_cells.edge();
    m_stats.cells = m_cells.numCells();

    m_cells.forEachOverlap([&](Index a, Index b) {
        ++m_stats.overlapsFound;
        emitPair(ps, a, b, region, out.pairs);
    });
    largePass(ps, region, out);
    wallPass(ps, walls, region, out);

    if (m_config.sortByUid) {
        std::sort(out.pairs.begin(), out.pairs.end(), [&ps](Contact const& x, Contact const& y) {
            return std::pair(ps.uid(x.i), ps.uid(x.j)) < std::pair(ps.uid(y.i), ps.uid(y.j));
        });
        std::sort(out.walls.begin(), out.walls.end(),
                  [&ps](WallContact const& x, WallContact const& y) {
                      return std::pair(ps.uid(x.particle), x.wall) <
                             std::pair(ps.uid(y.particle), y.wall);
                  });
    }
}

void ContactDetector::largePass(ParticleStorage const& ps, core::AABB const& region,
                                ContactList& out) {
    if (m_large.empty())
        return;
    // Large against small: the cells of the ball.
    for (Index a : m_large) {
        m_stats.largeCellVisits +=
            m_cells.forEachOverlapWith(ps.position(a), ps.radius(a), [&](Index b) {
                ++m_stats.largeCandidates;
                ++m_stats.overlapsFound;
                emitPair(ps, a, b, region, out.pairs);
            });
    }
    // Large against large: sort by the lower bound along the axis where the large centres
    // spread most (fewest overlapping intervals), sweep while the next lower bound is below
    // the current upper bound.
    core::Vec3 lo = ps.position(m_large[0]), hi = lo;
    for (Index k : m_large) {
        lo = lo.cwiseMin(ps.position(k));
        hi = hi.cwiseMax(ps.position(k));
    }
    Eigen::Index axis = 0;
    (hi - lo).maxCoeff(&axis);
    auto lower = [&ps, axis](Index k) { return ps.position(k)[axis] - ps.radius(k); };
    std::sort(m_large.begin(), m_large.end(), [&](Index x, Index y) {
        return lower(x) < lower(y) || (lower(x) == lower(y) && ps.uid(x) < ps.uid(y));
    });
    for (std::size_t s = 0; s < m_large.size(); ++s) {
        Index const a = m_large[s];
        double const upper = ps.position(a)[axis] + ps.radius(a);
        for (std::size_t t = s + 1; t < m_large.size() && lower(m_large[t]) < upper; ++t) {
            Index const b = m_large[t];
            ++m_stats.largeCandidates;
            double const reach = ps.radius(a) + ps.radius(b);
            if ((ps.position(b) - ps.position(a)).squaredNorm() < reach * reach) {
                ++m_stats.overlapsFound;
                emitPair(ps, a, b, region, out.pairs);
            }
        }
    }
}

void ContactDetector::wallPass(ParticleStorage const& ps, WallList const& walls,
                               core::AABB const& region, ContactList& out) {
    if (walls.empty())
        return;
    for (Index k = 0, n = ps.size(); k < n; ++k) {
        if (ps.flags(k).isFixed())
            continue; // walls are fixed too
        core::Vec3 const& x = ps.position(k);
        double const r = ps.radius(k);
        for (std::size_t w = 0; w < walls.size(); ++w) {
            Wall const& wall = walls[w];
            double const delta = r - wall.distance(x);
            if (!(delta > 0.0))
                continue;
            ++m_stats.overlapsFound;
            core::Vec3 const p = x - (r - 0.5 * delta) * wall.normal;
            if (region.contains(p))
                out.walls.push_back(WallContact{k, w, p, wall.normal, delta});
        }
    }
}

std::vector<std::size_t> ContactDetector::spatialOrder() const {
    auto const cells = m_cells.membersInCellOrder();
    std::vector<std::size_t> order(cells.begin(), cells.end());
    order.insert(order.end(), m_large.begin(), m_large.end());
    return order;
}

std::size_t ContactDetector::bytes() const {
    return m_cells.bytes() + (m_small.capacity() + m_large.capacity()) * sizeof(std::size_t) +
           m_scratch.capacity() * sizeof(double);
}

} // namespace regolith::particles
