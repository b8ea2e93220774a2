#pragma once
/// The potential on the ghost cells beyond free-space faces, for the right-hand side and for
/// the gradient there. Two ways, chosen per solve by the same rule on every rank:
///  - direct: the exact sum -G Σ m_c / |x - x_c| over the occupied cells (all ranks' cells
///    gathered), when occupied cells x boundary cells <= kDirectWork: few grains, or mass
///    close to a face, where a truncated expansion is poor;
///  - multipole (Multipole.hpp): monopole + quadrupole about the centre of mass otherwise,
///    accurate when the mass sits well inside the domain (error O((a/d)^3) for an aggregate
///    of size a seen from distance d; exact for a sphere).
/// The multipole moments and the occupied-cell count take one all-reduce; the direct branch
/// adds one all-gather of the occupied cells.
#include "gravity/poisson/Multipole.hpp"

#include <vector>

namespace regolith::gravity {

class FreeSpaceBoundary {
public:
    /// Work bound (occupied cells x boundary cells) below which the direct sum is used.
    static constexpr double kDirectWork = 3.0e7;

    /// Computes what at() needs from density component 0. COLLECTIVE over `comm`.
    void update(core::Comm const& comm, CellField const& density, double G);
    /// Potential at x [length^2 / time^2]. Local.
    [[nodiscard]] double at(core::Vec3 const& x) const;
    [[nodiscard]] bool direct() const { return m_direct; }
    [[nodiscard]] MassMoments const& moments() const { return m_moments; }

private:
    MassMoments m_moments;
    double m_G = 0.0;
    bool m_direct = false;
    std::vector<double> m_cells; ///< direct: x, y, z, mass per occupied cell
};

} // namespace regolith::gravity
