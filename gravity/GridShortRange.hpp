#pragma once
/// P3M short-range correction for grid gravity (Hockney & Eastwood, ch. 7): the mesh force
/// between two grains closer than a few cells is too weak (softened over the kernel width);
/// P3M adds, for each such pair, the exact Newtonian force minus the mesh's own pair force.
/// The mesh pair force is measured once on this very mesh (calibration: a unit point mass
/// at a few sub-cell positions, the mesh acceleration interpolated on a lattice of
/// displacements around it, averaged over the lattice symmetries; also radially, for the
/// potential), so the correction cancels the mesh's softening and its anisotropy, and leaves
/// only how the mesh force depends on where a grain sits in its cell.
///
/// Pairs are the caller's: the particle side finds them with its contact detector's cell
/// structure (gravity/ knows no particles). Point-like grains are assumed (radius <~ h/2).
#include "gravity/GridGravity.hpp"

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
    /// The mesh's radial pair acceleration at distance r for unit G m (table, linear
    /// interpolation) [1 / length^2]. Local.
    [[nodiscard]] double meshPairAcceleration(double r) const;
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
    /// Correction to the potential at grain i due to grain j, per unit m_j [length² / (mass
    /// time²)]: -G (ψ(r) - ψ_mesh(r)) with ψ = 1 / sqrt(r² + ε²) and the mesh's pair
    /// potential ψ_mesh(r) = 1 / cutoff + ∫_r^cutoff mesh(s) ds (the table integrated with
    /// the trapezoid rule, taking the mesh as exact at the cut-off); 0 from the cut-off on.
    /// Local, pure.
    [[nodiscard]] double pairPotential(double r, double softening) const;
    /// The mesh potential a point grain feels from itself, per unit mass of it: -G ψ_mesh(0)
    /// [length² / (mass time²)]. A grain's mesh potential includes this; P3M subtracts it so
    /// that ½ Σ m φ is the pair energy alone, as for the direct sum. Local, pure.
    [[nodiscard]] double selfPotential() const;

private:
    double m_G = 0.0;
    double m_cutoff = 0.0;
    double m_dr = 0.0;           ///< table spacing [length]
    std::vector<double> m_table; ///< mesh(r) at r = (k + 1) * m_dr
    /// ∫_r^cutoff mesh(s) ds at r = k * m_dr (k = 0 .. ceil(cutoff / m_dr), 0 from the cut-off)
    std::vector<double> m_integral;
    double m_dv = 0.0;                ///< vector table spacing [length]
    int m_half = 0;                   ///< vector table: displacements (i, j, k) m_dv, |i| <= m_half
    std::vector<core::Vec3> m_vector; ///< meshPairVector at the lattice nodes, x fastest

    /// Fills m_vector from the raw offset-averaged table (3 doubles per node).
    void symmetrise(std::vector<double> const& raw, core::Vec3 const& spacing);
};

} // namespace regolith::gravity
