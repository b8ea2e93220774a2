#pragma once
/// Free-space boundary values from a multipole expansion of the cell mass about its centre
/// of mass: monopole and quadrupole (the dipole vanishes about the centre of mass). The
/// moments about a fixed origin take ONE all-reduce of 10 numbers; the shift to the centre
/// of mass is done afterwards (parallel-axis theorem), so no second reduction is needed.
///
/// Error it adds: the first neglected term is the octupole, O(G M a^3 / d^4) for a mass
/// distribution of size a seen at distance d; with the domain face twice the size of the
/// aggregate away this is a few 1e-3 of the monopole at worst, and zero for a sphere.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "gravity/field/CellField.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace regolith::gravity {

struct MassMoments {
    double mass = 0.0;                                    ///< [mass]
    core::Vec3 centre = core::Vec3::Zero();               ///< centre of mass [length]
    Eigen::Matrix3d quadrupole = Eigen::Matrix3d::Zero(); ///< sum m (3 s s^T - |s|^2 I)
    double occupiedCells = 0.0; ///< cells with non-zero mass, all ranks (same reduction)
};

/// This rank's occupied cells (density component 0 times cell volume non-zero, interior
/// cells) as x, y, z, mass, four doubles each. Local.
[[nodiscard]] std::vector<double> occupiedCells(CellField const& density);

/// Moments of the cell masses of all ranks, from each rank's occupiedCells(); `origin` is a
/// point near the mass, the same on every rank (e.g. the domain's centre).
/// COLLECTIVE over `comm` (one all-reduce).
[[nodiscard]] MassMoments massMoments(core::Comm const& comm, std::span<double const> cells,
                                      core::Vec3 const& origin);

/// The potential of the expansion at x [length^2 / time^2]: -G (M / d + d^T Q d / (2 d^5)),
/// d = x - centre. Pre: x not at the centre. Local.
[[nodiscard]] double multipolePotential(MassMoments const& m, double G, core::Vec3 const& x);

} // namespace regolith::gravity
