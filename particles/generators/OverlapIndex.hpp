#pragma once
/// "Does this sphere overlap a grain placed before?" for the generators, in O(1) per query
/// whatever the mix of grain sizes: a hierarchical spatial hash (Mirtich 1996, "Impulse-based
/// dynamic simulation of rigid body systems", PhD thesis, Berkeley, sec. 3.3; the scheme of
/// pe's / waLBerla's HashGrids). Each grain goes to the level whose cubic cell edge is the
/// power of two in [2r, 4r); a level is a hash map from cell to an intrusive list of grains,
/// so memory is O(grains) however large the domain, and a query visits, per non-empty level,
/// the cells within (query radius + largest radius of that level) of the query point. A
/// boulder among small grains is one entry of a coarse level, not thousands of cells; a
/// query that would visit more cells than a level has grains tests those grains directly.
#include "core/math/Vec3.hpp"
#include "particles/generators/GeneratorDomain.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

namespace regolith::particles {

class OverlapIndex {
public:
    /// Pre: on every periodic axis, a grain's diameter is below the period (validated), so the
    /// images at one period of distance are the only ones that can touch.
    explicit OverlapIndex(GeneratorDomain const& domain);

    /// Adds a grain. Pre: `centre` inside the domain (wrapped on periodic axes), radius > 0.
    void insert(core::Vec3 const& centre, double radius);

    /// Does the sphere (centre, radius) overlap (spheresOverlap) any inserted grain, or a
    /// periodic image of one? Pre: `centre` inside the domain, radius > 0.
    [[nodiscard]] bool overlaps(core::Vec3 const& centre, double radius) const;

    [[nodiscard]] std::size_t size() const { return m_radius.size(); }
    [[nodiscard]] bool empty() const { return m_radius.empty(); }

private:
    struct Cell {
        std::int64_t i, j, k;
        friend bool operator==(Cell const&, Cell const&) = default;
    };
    struct CellHash {
        std::size_t operator()(Cell const& c) const noexcept;
    };
    struct Level {
        double edge = 1.0;                   ///< cell edge, a power of two
        double maxRadius = 0.0;              ///< largest grain radius stored here
        std::array<std::int64_t, 3> cells{}; ///< cells per axis covering the domain
        std::unordered_map<Cell, std::uint32_t, CellHash> head; ///< first grain of a cell
        std::vector<std::uint32_t> members; ///< all grains of the level, for huge queries
    };
    static constexpr std::uint32_t kEnd = ~std::uint32_t{0};

    Level& levelFor(double radius);
    [[nodiscard]] bool overlapsInLevel(Level const& level, core::Vec3 const& centre,
                                       double radius) const;

    GeneratorDomain m_domain;
    std::map<int, Level> m_levels; ///< by exponent of the cell edge
    std::vector<core::Vec3> m_centre;
    std::vector<double> m_radius;
    std::vector<std::uint32_t> m_next; ///< next grain in the same cell, or kEnd
};

} // namespace regolith::particles
