#include "particles/generators/OverlapIndex.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::particles {

std::size_t OverlapIndex::CellHash::operator()(Cell const& c) const noexcept {
    // Large odd multipliers (as in Teschner et al. 2003, "Optimized spatial hashing for
    // collision detection of deformable objects") mixing the three cell coordinates.
    auto const h = static_cast<std::uint64_t>(c.i) * 73856093ULL ^
                   static_cast<std::uint64_t>(c.j) * 19349663ULL ^
                   static_cast<std::uint64_t>(c.k) * 83492791ULL;
    return static_cast<std::size_t>(h ^ (h >> 29));
}

OverlapIndex::OverlapIndex(GeneratorDomain const& domain)
    : m_domain(domain) {}

OverlapIndex::Level& OverlapIndex::levelFor(double radius) {
    int exponent = 0;
    // 2r = m * 2^exponent with m in [0.5, 1): the edge 2^exponent lies in (2r, 4r].
    (void)std::frexp(2.0 * radius, &exponent);
    auto [it, inserted] = m_levels.try_emplace(exponent);
    Level& level = it->second;
    if (inserted) {
        level.edge = std::ldexp(1.0, exponent);
        for (int a = 0; a < 3; ++a) {
            double const n = std::floor(m_domain.period(a) / level.edge) + 1.0;
            // A level finer than 2^62 cells per axis would mean grains 1e-18 of the domain.
            if (!(n < 0x1.0p62))
                throw core::InputError("particle generators: grain radius " +
                                       std::to_string(radius) +
                                       " is too small for the domain size");
            level.cells[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(n);
        }
    }
    return level;
}

void OverlapIndex::insert(core::Vec3 const& centre, double radius) {
    if (m_radius.size() >= kEnd)
        throw core::Error("OverlapIndex: more than 2^32 - 1 grains on one rank");
    Level& level = levelFor(radius);
    Cell c{};
    std::array<std::int64_t*, 3> const idx{&c.i, &c.j, &c.k};
    for (int a = 0; a < 3; ++a) {
        auto const n = level.cells[static_cast<std::size_t>(a)];
        auto const i =
            static_cast<std::int64_t>(std::floor((centre[a] - m_domain.box.min[a]) / level.edge));
        *idx[static_cast<std::size_t>(a)] = std::clamp<std::int64_t>(i, 0, n - 1);
    }
    auto const id = static_cast<std::uint32_t>(m_radius.size());
    auto [it, inserted] = level.head.try_emplace(c, id);
    m_next.push_back(inserted ? kEnd : it->second);
    it->second = id;
    level.members.push_back(id);
    m_centre.push_back(centre);
    m_radius.push_back(radius);
    level.maxRadius = std::max(level.maxRadius, radius);
}

bool OverlapIndex::overlaps(core::Vec3 const& centre, double radius) const {
    for (auto const& [exponent, level] : m_levels)
        if (overlapsInLevel(level, centre, radius))
            return true;
    return false;
}

bool OverlapIndex::overlapsInLevel(Level const& level, core::Vec3 const& centre,
                                   double radius) const {
    double const reach = radius + level.maxRadius;
    // Periodic images of the query point that can reach grains across a periodic face.
    std::array<std::array<double, 3>, 3> shifts{};
    std::array<int, 3> nShifts{1, 1, 1};
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        shifts[ua][0] = 0.0;
        if (!m_domain.periodic[ua])
            continue;
        double const length = m_domain.period(a);
        if (centre[a] - reach < m_domain.box.min[a])
            shifts[ua][static_cast<std::size_t>(nShifts[ua]++)] = length;
        if (centre[a] + reach > m_domain.box.max[a])
            shifts[ua][static_cast<std::size_t>(nShifts[ua]++)] = -length;
    }
    for (int sx = 0; sx < nShifts[0]; ++sx)
        for (int sy = 0; sy < nShifts[1]; ++sy)
            for (int sz = 0; sz < nShifts[2]; ++sz) {
                core::Vec3 const q = centre + core::Vec3(shifts[0][static_cast<std::size_t>(sx)],
                                                         shifts[1][static_cast<std::size_t>(sy)],
                                                         shifts[2][static_cast<std::size_t>(sz)]);
                std::array<std::int64_t, 3> lo{};
                std::array<std::int64_t, 3> hi{};
                bool empty = false;
                for (int a = 0; a < 3; ++a) {
                    auto const ua = static_cast<std::size_t>(a);
                    double const rel = q[a] - m_domain.box.min[a];
                    double const first = std::floor((rel - reach) / level.edge);
                    double const last = std::floor((rel + reach) / level.edge);
                    double const maxCell = static_cast<double>(level.cells[ua] - 1);
                    if (last < 0.0 || first > maxCell) {
                        empty = true;
                        break;
                    }
                    lo[ua] = static_cast<std::int64_t>(std::max(first, 0.0));
                    hi[ua] = static_cast<std::int64_t>(std::min(last, maxCell));
                }
                if (empty)
                    continue;
                double cellsInRange = 1.0;
                for (std::size_t a = 0; a < 3; ++a)
                    cellsInRange *= static_cast<double>(hi[a] - lo[a] + 1);
                if (cellsInRange > static_cast<double>(level.members.size())) {
                    for (auto const g : level.members)
                        if (spheresOverlap(q, radius, m_centre[g], m_radius[g]))
                            return true;
                    continue;
                }
                for (auto k = lo[2]; k <= hi[2]; ++k)
                    for (auto j = lo[1]; j <= hi[1]; ++j)
                        for (auto i = lo[0]; i <= hi[0]; ++i) {
                            auto const it = level.head.find(Cell{i, j, k});
                            if (it == level.head.end())
                                continue;
                            for (auto g = it->second; g != kEnd; g = m_next[g])
                                if (spheresOverlap(q, radius, m_centre[g], m_radius[g]))
                                    return true;
                        }
            }
    return false;
}

} // namespace regolith::particles
