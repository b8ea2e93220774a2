#include "particles/generators/RegionSet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace regolith::particles {

namespace {

using Interval = std::pair<double, double>;

/// The parts of [lo, hi] inside the domain along `axis`, periodic images folded in.
std::vector<Interval> foldAxis(double lo, double hi, int axis, GeneratorDomain const& domain) {
    double const dMin = domain.box.min[axis];
    double const dMax = domain.box.max[axis];
    std::vector<Interval> out;
    if (!domain.periodic[static_cast<std::size_t>(axis)]) {
        if (lo <= dMax && hi >= dMin)
            out.emplace_back(std::max(lo, dMin), std::min(hi, dMax));
        return out;
    }
    double const length = dMax - dMin;
    if (hi - lo >= length) {
        out.emplace_back(dMin, dMax);
        return out;
    }
    // Extent below one period: at most two images (three when touching) reach the domain.
    auto const nLo = static_cast<long long>(std::ceil((dMin - hi) / length));
    auto const nHi = static_cast<long long>(std::floor((dMax - lo) / length));
    for (long long n = nLo; n <= nHi; ++n) {
        double const shift = static_cast<double>(n) * length;
        double const a = lo + shift;
        double const b = hi + shift;
        if (a <= dMax && b >= dMin)
            out.emplace_back(std::max(a, dMin), std::min(b, dMax));
    }
    return out;
}

} // namespace

void RegionSet::add(core::AABB const& box, double margin, GeneratorDomain const& domain) {
    std::array<std::vector<Interval>, 3> parts;
    for (int a = 0; a < 3; ++a) {
        parts[static_cast<std::size_t>(a)] =
            foldAxis(box.min[a] - margin, box.max[a] + margin, a, domain);
        if (parts[static_cast<std::size_t>(a)].empty())
            return;
    }
    for (auto const& [x0, x1] : parts[0])
        for (auto const& [y0, y1] : parts[1])
            for (auto const& [z0, z1] : parts[2]) {
                core::AABB const b{core::Vec3(x0, y0, z0), core::Vec3(x1, y1, z1)};
                m_bounds = m_boxes.empty() ? b
                                           : core::AABB{m_bounds.min.cwiseMin(b.min),
                                                        m_bounds.max.cwiseMax(b.max)};
                m_boxes.push_back(b);
            }
}

bool RegionSet::containsClosed(core::Vec3 const& p) const {
    auto inside = [&](core::AABB const& b) {
        return (p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all();
    };
    if (m_boxes.empty() || !inside(m_bounds))
        return false;
    return std::any_of(m_boxes.begin(), m_boxes.end(), inside);
}

} // namespace regolith::particles
