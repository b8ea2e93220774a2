#pragma once
/// P3M short-range correction for grid gravity (Hockney & Eastwood, ch. 7): the mesh force
/// between two grains closer than a few cells is too weak (softened over the kernel width);
/// P3M adds, for each such pair, the exact Newtonian force minus the mesh's own pair force.
/// The mesh pair force is measured once on this very mesh (calibration: a unit point mass
/// at a few sub-cell positions, the mesh acceleration interpolated on a lattice of
/// displacements around it, averaged over the lattice symmetries), so the correction cancels
/// the mesh's softening and its anisotropy, and leaves only how the mesh force depends on
/// where a grain sits in its cell. The energy needs no such average: the mesh potential is
/// linear in the deposit, so the potential one grain's deposit gives at another's (and at
/// its own) is exactly the deposit weights applied to the potential of a unit mass in one
/// cell, measured once as a table of cell offsets (Hockney & Eastwood, ch. 7: the mesh
/// Green's function).
///
/// Pairs are the caller's: the particle side finds them with its contact detector's cell
/// structure (gravity/ knows no particles). Point-like grains are assumed (radius <~ h/2).
#include "gravity/GridGravity.hpp"
#include "gravity/MeshPotentialTable.hpp"

#include <cstdint>
#include <vector>

namespace regolith::gravity {

class GridShortRange {
public:
    /// Calibrates on `gravity` (overwrites its fields: call before the first update() of a
    /// step). `cutoffCells`: pairs closer than cutoffCells * h are corrected (>= 2; 4 is
    /// where the mesh force is within ~1 % for TSC with the fourth-order gradient).
    /// Pre: a free-space domain at least 4 cutoffs wide. COLLECTIVE over `comm`.
    GridShortRange(core::Comm const& comm, GridGravity& gravity, double cutoffCells = 4.0);

    /// Cut-off distance [length].
    [[nodiscard]] double cutoff() const { return m_cutoff; }
    /// The mesh's acceleration at displacement e from a unit (G m = 1) point source, from the
    /// lattice table (spacing h/4, trilinear; averaged over source offsets and the lattice
    /// symmetries, odd in e) [1 / length^2]. Pre: |e_a| <= cutoff. Local, pure.
    [[nodiscard]] core::Vec3 meshPairVector(core::Vec3 const& e) const;
    /// Correction to the acceleration of grain i due to grain j of mass mj at separation
    /// d = x_j - x_i: mj * pairCorrection(d, 0). Local, pure.
    [[nodiscard]] core::Vec3 correction(core::Vec3 const& d, double mj) const;
    /// Correction per unit m_j, with Plummer softening ε [length] inside the cut-off (the
    /// mesh itself is not softened, so use ε well below the cut-off): the exact pair
    /// acceleration G d / (r² + ε²)^{3/2} minus the mesh's, -G T(-d) = G meshPairVector(d),
    /// for 0 < r < cutoff, else zero [length / (mass time²)]. The vector table removes the
    /// mesh's anisotropy (along the axes the mesh is ~12 % weaker at 2 h than along
    /// diagonals), which a radial table cannot. Odd in d: the pair's corrections are equal
    /// and opposite. Local, pure.
    [[nodiscard]] core::Vec3 pairCorrection(core::Vec3 const& d, double softening) const;
    /// Correction to the potential at grain i (at xi) due to grain j (at xj, the image
    /// nearest to xi) per unit m_j [length² / (mass time²)]: the exact -G / sqrt(r² + ε²)
    /// minus what the mesh gave, meshPotential(xi, xj), plus the table's regular part at the
    /// cut-off (images and background on a periodic domain, ~0 in free space), so that it
    /// vanishes at the cut-off; 0 from the cut-off on. Local, pure.
    [[nodiscard]] double pairPotential(core::Vec3 const& xi, core::Vec3 const& xj,
                                       double softening) const;
    /// The mesh potential at xi due to a grain at xj per unit mass of it
    /// (MeshPotentialTable::meshPotential). Local, pure.
    [[nodiscard]] double meshPotential(core::Vec3 const& xi, core::Vec3 const& xj) const {
        return m_table.meshPotential(xi, xj);
    }
    /// What a point grain at x feels from its own deposit, less the table's regular part at
    /// the cut-off (MeshPotentialTable::selfPotential): P3M subtracts it. Local, pure.
    [[nodiscard]] double selfPotential(core::Vec3 const& x) const {
        return m_table.selfPotential(x);
    }

private:
    /// Fills m_vector from the raw offset-averaged table (3 doubles per node).
    void symmetrise(std::vector<double> const& raw, core::Vec3 const& spacing);

    double m_G = 0.0;
    double m_cutoff = 0.0;
    MeshPotentialTable m_table;       ///< the energies (pairs within the cut-off, self)
    double m_dv = 0.0;                ///< vector table spacing [length]
    int m_half = 0;                   ///< vector table: displacements (i, j, k) m_dv, |i| <= m_half
    std::vector<core::Vec3> m_vector; ///< meshPairVector at the lattice nodes, x fastest
};

} // namespace regolith::gravity
