#pragma once
/// The mesh's own potential, measured once: the potential at cell offsets of a unit mass in
/// one cell (the mesh's Green's function, Hockney & Eastwood, ch. 7), from which the mesh
/// potential one grain's deposit gives at another's (and at its own) follows exactly, since
/// the mesh potential is linear in the deposit: the deposit weights applied to the table. P3M
/// takes its close pairs' and its grains' self-energy from it (GridShortRange); pm the
/// self-energy, which ½ Σ m φ of the mesh would otherwise include (−0.61 to −0.64 G m²/h
/// for a point, depending on where it sits in its cell).
#include "gravity/GridGravity.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace regolith::gravity {

/// The permutations of the axes that map the mesh onto itself: all six with cubic cells,
/// the identity otherwise (with the eight reflections, the lattice symmetries the measured
/// tables are averaged over).
[[nodiscard]] std::vector<std::array<int, 3>> axisPermutations(core::Vec3 const& spacing);

class MeshPotentialTable {
public:
    /// Measures the table on `gravity` (one solve from a unit mass in the cell at the domain's
    /// centre: overwrites its fields) for grains up to `radius` [length] apart, and the
    /// table's regular part at `radius` (images and background on a periodic domain, ~0 in
    /// free space). COLLECTIVE over `comm`.
    MeshPotentialTable(core::Comm const& comm, GridGravity& gravity, double radius);

    /// The mesh potential at xi due to a point grain at xj per unit mass of it (the deposit of
    /// xj read with the weights of xi) [length² / (mass time²)]. Pre: |xi - xj| <= radius
    /// per axis. Local, pure.
    [[nodiscard]] double meshPotential(core::Vec3 const& xi, core::Vec3 const& xj) const;
    /// What a point grain at x feels from its own deposit, per unit mass of it, less the
    /// regular part: ½ Σ m φ includes it, so that subtracting it leaves the pairs' energy alone
    /// in free space, as for the direct sum, and each grain its images' share on a periodic
    /// domain. Local, pure.
    [[nodiscard]] double selfPotential(core::Vec3 const& x) const;
    /// The same for a grain of `radius` deposited as the equal-weight points of ballSamples
    /// (one point up to half a cell): the mean over pairs of its points while its diameter is
    /// within the table (`radius` of the constructor), beyond that a uniform ball's
    /// -6/5 G / r (the mesh resolves it; a boulder 100 cells wide has ~10^6 samples). Local,
    /// pure.
    [[nodiscard]] double selfPotential(core::Vec3 const& x, double radius) const;
    /// The regular part at `radius` [length² / (mass time²)].
    [[nodiscard]] double regular() const { return m_regular; }

private:
    /// Fills m_cell: the potential at cell offsets up to m_reach of a unit G m in one cell at
    /// `source`, averaged over the lattice symmetries; offsets the domain does not hold take
    /// the Newtonian value (the mesh follows it to ~1 % from 4 cells on). COLLECTIVE.
    void measureCellPotential(core::Comm const& comm, GridGravity& gravity,
                              core::Vec3 const& source);
    /// m_cell at offset (i, j, k), each in [-m_reach, m_reach].
    [[nodiscard]] double cellPotential(std::int64_t i, std::int64_t j, std::int64_t k) const;

    CellLayout const* m_layout = nullptr;
    Assignment m_assignment = Assignment::Tsc;
    double m_G = 0.0;
    double m_radius = 0.0;
    std::int64_t m_reach = 0;   ///< offsets |i| <= m_reach
    std::vector<double> m_cell; ///< the table, x fastest
    double m_regular = 0.0;     ///< the regular part at m_radius (see above)
};

} // namespace regolith::gravity
