#pragma once
/// P3M short-range correction for grid gravity (Hockney & Eastwood, ch. 7): the mesh force
/// between two grains closer than a few cells is too weak (softened over the kernel width);
/// P3M adds, for each such pair, the exact Newtonian force minus the mesh's own pair force.
/// The mesh pair force is measured once on this very mesh (calibration: a unit point mass
/// at a few sub-cell positions, the mesh acceleration interpolated at test points around it
/// in many directions, averaged radially), so the correction cancels the mesh's softening
/// and leaves only its anisotropy (a few % at one cell, shrinking with distance).
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
    /// Correction to the acceleration of grain i due to grain j of mass mj at separation
    /// d = x_j - x_i: G mj d̂ (1/r² - mesh(r)) for r < cutoff, else zero. Local, pure.
    [[nodiscard]] core::Vec3 correction(core::Vec3 const& d, double mj) const;

    /// The same correction as a factor, with Plummer softening ε [length] inside the cut-off
    /// (the mesh itself is not softened, so use ε well below the cut-off): the acceleration of
    /// grain i due to grain j is pairFactor(r, ε) * m_j * (x_j - x_i), where
    /// pairFactor = G (r / (r² + ε²)^{3/2} - mesh(r)) / r for 0 < r < cutoff, else 0
    /// [1 / (mass time²)]. Local, pure.
    [[nodiscard]] double pairFactor(double r, double softening) const;
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
};

} // namespace regolith::gravity
