#pragma once
/// Exact geometry of a block forest: every block is a box of an integer lattice (the cells of
/// the finest level), and real coordinates are derived from lattice planes by one function, so
/// that neighbouring blocks share bit-identical faces and every topological decision
/// (touching, containment, 2:1 balance, periodic images) is made in integers.
#include "core/math/AABB.hpp"
#include "domain/BlockId.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <utility>

namespace regolith::domain {

using LatticeIndex = std::int64_t;
using LatticeCell = std::array<LatticeIndex, 3>;
/// Periodic image of the domain, in whole periods per axis: image o covers
/// [min + o * extent, max + o * extent). Always 0 on a non-periodic axis.
using PeriodicImage = std::array<int, 3>;

/// Half-open box [lo, hi) of lattice cells.
struct LatticeBox {
    LatticeCell lo{0, 0, 0};
    LatticeCell hi{0, 0, 0};

    [[nodiscard]] bool contains(LatticeCell const& c) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] < lo[a] || c[a] >= hi[a])
                return false;
        return true;
    }
    /// Closed boxes share at least a face, edge or corner (or overlap).
    [[nodiscard]] bool touches(LatticeBox const& o) const {
        for (int a = 0; a < 3; ++a)
            if (lo[a] > o.hi[a] || o.lo[a] > hi[a])
                return false;
        return true;
    }
    [[nodiscard]] LatticeBox shifted(LatticeCell const& s) const {
        LatticeBox b = *this;
        for (int a = 0; a < 3; ++a) {
            b.lo[a] += s[a];
            b.hi[a] += s[a];
        }
        return b;
    }
    friend bool operator==(LatticeBox const&, LatticeBox const&) = default;
};

/// The image o and the wrapped value w of coordinate x on a periodic axis spanning [lo, hi):
/// o decided against the boundaries lo + o (hi - lo) that shifted boxes use, w = x - o (hi -
/// lo) clamped into [lo, hi). Image 0 and x itself where lo <= x < hi. Pre: x finite. The one
/// rule for the periodic image of a point (ForestGeometry::locate and wrap, and contact
/// detection's PeriodicFrame).
[[nodiscard]] std::pair<int, double> wrapOnAxis(double lo, double hi, double x);

/// Lattice and coordinate maps of one forest. The lattice has rootBlocks[a] * 2^maxLevel cells
/// on axis a; root block (i, j, k) covers cells [i, i+1) * 2^maxLevel etc.; the root index is
/// i + nx * (j + ny * k). Cheap to copy; every rank holds the same one.
class ForestGeometry {
public:
    /// Pre: a valid spec (see SpecValidation.hpp): max > min, rootBlocks >= 1,
    /// 0 <= maxLevel <= BlockId::kMaxLevel.
    ForestGeometry(core::AABB const& domain, std::array<int, 3> rootBlocks,
                   std::array<bool, 3> periodic, int maxLevel);

    [[nodiscard]] core::AABB const& domain() const { return m_domain; }
    [[nodiscard]] std::array<int, 3> const& rootBlocks() const { return m_rootBlocks; }
    [[nodiscard]] std::array<bool, 3> const& periodic() const { return m_periodic; }
    /// Deepest level of any block; the lattice resolves it.
    [[nodiscard]] int maxLevel() const { return m_maxLevel; }
    [[nodiscard]] std::uint64_t rootCount() const;
    /// Lattice cells per root block and axis: 2^maxLevel.
    [[nodiscard]] LatticeIndex rootSize() const { return LatticeIndex{1} << m_maxLevel; }
    /// Lattice cells across the domain on `axis`.
    [[nodiscard]] LatticeIndex latticeSize(int axis) const { return m_latticeSize[axis]; }

    /// Real coordinate of lattice plane i in [0, latticeSize(axis)]: exactly min at 0 and max
    /// at the end, monotone in between (std::lerp), the same value for every block using it.
    [[nodiscard]] double coordinate(int axis, LatticeIndex i) const;

    [[nodiscard]] std::uint64_t rootIndex(LatticeCell const& rootCoord) const;
    [[nodiscard]] LatticeCell rootCoord(std::uint64_t rootIndex) const;
    /// Lattice box of a block. Pre: id.level() <= maxLevel(), root index < rootCount().
    [[nodiscard]] LatticeBox latticeBox(BlockId id) const;
    /// Real box of lattice box b (faces from coordinate()).
    [[nodiscard]] core::AABB box(LatticeBox const& b) const;
    [[nodiscard]] core::AABB box(BlockId id) const { return box(latticeBox(id)); }
    /// The id of the level-`level` block (leaf or not) whose box holds `cell`.
    /// Pre: cell inside the lattice, level <= maxLevel().
    [[nodiscard]] BlockId blockAt(LatticeCell const& cell, int level) const;

    /// The shift of a link to periodic image `image`: -image * extent (see Block.hpp).
    [[nodiscard]] core::Vec3 shift(PeriodicImage const& image) const;
    /// Maps p into [min, max) on every periodic axis (unchanged on the others). The result is
    /// clamped into the half-open domain, so rounding never yields max itself.
    [[nodiscard]] core::Vec3 wrap(core::Vec3 const& p) const;
    /// min <= p < max on every non-periodic axis (periodic axes accept any finite value).
    [[nodiscard]] bool insideDomain(core::Vec3 const& p) const;

    /// Where a point lies: the lattice cell of wrap(p) and the image of the domain holding p.
    struct Location {
        LatticeCell cell;
        PeriodicImage image;
    };
    /// nullopt if p is outside the domain on a non-periodic axis or not finite.
    [[nodiscard]] std::optional<Location> locate(core::Vec3 const& p) const;

private:
    /// wrapOnAxis on axis `axis` of the domain. Pre: x finite.
    [[nodiscard]] std::pair<int, double> wrapAxis(int axis, double x) const {
        return wrapOnAxis(m_domain.min[axis], m_domain.max[axis], x);
    }
    /// The cell i with coordinate(i) <= x < coordinate(i + 1). Pre: min <= x < max.
    [[nodiscard]] LatticeIndex cellOnAxis(int axis, double x) const;

    core::AABB m_domain;
    std::array<int, 3> m_rootBlocks;
    std::array<bool, 3> m_periodic;
    int m_maxLevel;
    LatticeCell m_latticeSize;
};

} // namespace regolith::domain
