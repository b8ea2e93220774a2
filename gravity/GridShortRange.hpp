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

private:
    double m_G = 0.0;
    double m_cutoff = 0.0;
    double m_dr = 0.0;           ///< table spacing [length]
    std::vector<double> m_table; ///< mesh(r) at r = (k + 1) * m_dr
};

} // namespace regolith::gravity
