#include "particles/generators/LatticeSites.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <numbers>

namespace regolith::particles {

namespace {
/// Distance between rows of a triangular layer, in units of the sphere diameter.
double const kRowStep = std::numbers::sqrt3 / 2.0;
/// Distance between hcp layers, in units of the sphere diameter: sqrt(2/3).
double const kLayerStep = std::sqrt(2.0 / 3.0);
} // namespace

double latticePeriod(LatticeKind kind, double spacing, int axis) {
    if (kind == LatticeKind::SimpleCubic || axis == 0)
        return spacing;
    return spacing * 2.0 * (axis == 1 ? kRowStep : kLayerStep);
}

LatticeSites::LatticeSites(LatticeSpec const& spec, GeneratorDomain const& domain,
                           std::string const& entryKey)
    : m_kind(spec.lattice)
    , m_spacing(spec.spacing)
    , m_radius(spec.radius)
    , m_region(spec.region)
    , m_periodic(domain.periodic)
    , m_origin(spec.region.min.array() + 0.5 * spec.spacing) {
    if (m_kind == LatticeKind::HexagonalClosePacked)
        m_step = {1.0, kRowStep, kLayerStep};
    double candidates = 1.0;
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        double const estimate =
            std::ceil((m_region.max[a] - m_origin[a]) / (m_spacing * m_step[ua]));
        candidates *= std::max(estimate, 1.0);
        if (!(candidates <= kMaxLatticeCandidates))
            throw core::InputError(fmt::format(
                "{}.spacing: the lattice would have more than 2^40 sites (spacing {} in a "
                "region of extent [{}, {}, {}]); increase spacing or shrink the region",
                entryKey, m_spacing, m_region.extent().x(), m_region.extent().y(),
                m_region.extent().z()));
        // n = number of indices whose zero-offset coordinate lies below region.max, found
        // with the same expression as coord() so no rounding can disagree.
        auto n = static_cast<std::int64_t>(std::max(estimate, 0.0));
        while (n > 0 && coord(a, n - 1, 0.0) >= m_region.max[a])
            --n;
        while (coord(a, n, 0.0) < m_region.max[a])
            ++n;
        m_extent[ua] = n;
    }
}

std::uint64_t LatticeSites::capacity() const {
    return static_cast<std::uint64_t>(m_extent[0]) * static_cast<std::uint64_t>(m_extent[1]) *
           static_cast<std::uint64_t>(m_extent[2]);
}

core::Vec3 LatticeSites::centre(std::int64_t i, std::int64_t j, std::int64_t k) const {
    if (m_kind == LatticeKind::SimpleCubic)
        return {coord(0, i, 0.0), coord(1, j, 0.0), coord(2, k, 0.0)};
    // hcp (Conway & Sloane ch. 1): rows of a layer shifted by half a spacing in x when
    // j + k is odd; odd layers (B) shifted by a third of a row step in y.
    double const y = coord(1, j, (k % 2 != 0) ? 1.0 / 3.0 : 0.0);
    if (!shiftedRow(j, k))
        return {coord(0, i, 0.0), y, coord(2, k, 0.0)};
    // On a periodic x the shifted rows start at region.min itself, so that their site at
    // region.max is that one's image and every row has the same sites on the period;
    // written without the origin so that the first is exactly region.min.
    double const x =
        m_periodic[0] ? m_region.min.x() + m_spacing * static_cast<double>(i) : coord(0, i, 0.5);
    return {x, y, coord(2, k, 0.0)};
}

bool LatticeSites::used(core::Vec3 const& c) const {
    for (int a = 0; a < 3; ++a) {
        if (m_periodic[static_cast<std::size_t>(a)]) {
            if (c[a] < m_region.min[a] || c[a] >= m_region.max[a])
                return false;
        } else if (c[a] - m_radius < m_region.min[a] || c[a] + m_radius > m_region.max[a]) {
            return false;
        }
    }
    return true;
}

std::uint64_t LatticeSites::linearIndex(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::uint64_t>(i) +
           static_cast<std::uint64_t>(m_extent[0]) *
               (static_cast<std::uint64_t>(j) +
                static_cast<std::uint64_t>(m_extent[1]) * static_cast<std::uint64_t>(k));
}

std::array<std::int64_t, 2> LatticeSites::indexRange(int axis, double lo, double hi) const {
    auto const ua = static_cast<std::size_t>(axis);
    double const step = m_spacing * m_step[ua];
    double const n = static_cast<double>(m_extent[ua]);
    // Offsets are below one step, so one extra index on each side covers every rounding.
    double const first = std::max(std::floor((lo - m_origin[axis]) / step) - 1.0, 0.0);
    double const last = std::min(std::ceil((hi - m_origin[axis]) / step) + 1.0, n - 1.0);
    if (lo > hi || first > last)
        return {0, -1};
    return {static_cast<std::int64_t>(first), static_cast<std::int64_t>(last)};
}

} // namespace regolith::particles
