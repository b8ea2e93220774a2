#pragma once
/// The sites of a `kind = "lattice"` entry (sc or hcp, see LatticeSpec for the geometry and
/// which sites are used), enumerated box by box so a rank touches only the sites near its
/// blocks. Sites are numbered by a rank-independent linear index over a bounding index box,
/// i + n_i * (j + n_j * k); unused candidates leave gaps in the numbering.
#include "core/math/AABB.hpp"
#include "particles/generators/GeneratorDomain.hpp"
#include "particles/generators/GeneratorSpec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace regolith::particles {

/// The lattice's period along `axis` (0, 1, 2) [length]: the spacing for sc; for hcp the
/// spacing along x, two rows (sqrt(3) spacings) along y and two layers (2 sqrt(2/3) spacings)
/// along z. A periodic domain whose extent is not a multiple of it leaves the sites across
/// its face closer or farther apart than inside.
[[nodiscard]] double latticePeriod(LatticeKind kind, double spacing, int axis);

class LatticeSites {
public:
    /// Pre: `spec` validated (validateParticleSpecs). Throws core::InputError naming
    /// `entryKey` (e.g. "particles[2]") if the bounding index box holds more than
    /// kMaxLatticeCandidates sites.
    LatticeSites(LatticeSpec const& spec, GeneratorDomain const& domain,
                 std::string const& entryKey);

    /// Candidate index ranges [0, n) along i, j, k: every used site lies inside.
    [[nodiscard]] std::array<std::int64_t, 3> const& extents() const { return m_extent; }
    /// Number of candidate sites, i.e. the width of the entry's uid range.
    [[nodiscard]] std::uint64_t capacity() const;
    /// Centre of site (i, j, k) [length]. The one expression used for every site everywhere.
    [[nodiscard]] core::Vec3 centre(std::int64_t i, std::int64_t j, std::int64_t k) const;
    /// Is a site with this centre used (inside the region by the rule of LatticeSpec)?
    [[nodiscard]] bool used(core::Vec3 const& centre) const;
    /// i + n_i * (j + n_j * k).
    [[nodiscard]] std::uint64_t linearIndex(std::int64_t i, std::int64_t j, std::int64_t k) const;

    /// Calls visit(linearIndex, centre) for every used site whose centre lies in `box`
    /// (closed), in increasing linear index. Cost O(sites near the box).
    template <class Visit>
    void forEachSiteIn(core::AABB const& box, Visit&& visit) const;

    /// Largest bounding index box accepted: the uid counter field of a Uid.
    static constexpr double kMaxLatticeCandidates = 0x1.0p40;

private:
    /// Coordinate along `axis` of index `n` with the row/layer offset `offset` (in units of
    /// the axis step: 0, 1/2 or 1/3).
    [[nodiscard]] double coord(int axis, std::int64_t n, double offset) const {
        return m_origin[axis] + m_spacing * (m_step[static_cast<std::size_t>(axis)] *
                                             (static_cast<double>(n) + offset));
    }
    /// hcp: rows with j + k odd are shifted by half a spacing in x.
    [[nodiscard]] bool shiftedRow(std::int64_t j, std::int64_t k) const {
        return m_kind == LatticeKind::HexagonalClosePacked && (j + k) % 2 != 0;
    }
    /// Conservative index range along `axis` for coordinates in [lo, hi]; empty if lo > hi.
    [[nodiscard]] std::array<std::int64_t, 2> indexRange(int axis, double lo, double hi) const;

    LatticeKind m_kind;
    double m_spacing;
    double m_radius;
    core::AABB m_region;
    std::array<bool, 3> m_periodic;
    core::Vec3 m_origin;
    std::array<double, 3> m_step{1.0, 1.0, 1.0}; ///< axis step in units of the spacing
    std::array<std::int64_t, 3> m_extent{0, 0, 0};
};

template <class Visit>
void LatticeSites::forEachSiteIn(core::AABB const& box, Visit&& visit) const {
    auto const rk = indexRange(2, box.min.z(), box.max.z());
    auto const rj = indexRange(1, box.min.y(), box.max.y());
    auto const ri = indexRange(0, box.min.x(), box.max.x());
    for (auto k = rk[0]; k <= rk[1]; ++k)
        for (auto j = rj[0]; j <= rj[1]; ++j)
            for (auto i = ri[0]; i <= ri[1]; ++i) {
                core::Vec3 const c = centre(i, j, k);
                if ((c.array() >= box.min.array()).all() && (c.array() <= box.max.array()).all() &&
                    used(c))
                    visit(linearIndex(i, j, k), c);
            }
}

} // namespace regolith::particles
