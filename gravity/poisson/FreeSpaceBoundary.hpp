#pragma once
/// The potential at the centres of the ghost cells beyond free-space faces, for the
/// right-hand side of the Poisson solve and for the gradient there: the free-space field of
/// the cell masses, -G Σ m_c / |x - x_c|, evaluated in batches. Two ways, chosen per update by
/// the same rule on every rank:
///  - tree (default): the occupied cells of all ranks are gathered and put in an octree with
///    monopole + quadrupole cells; a batch of nearby targets shares one walk with opening
///    angle kTheta (InteractionList.hpp) and the vectorised list kernel. The error it adds is
///    that of Barnes–Hut with quadrupoles at θ = 0.2: at most 5e-5 of max |φ| on the
///    boundary (tests/gravity/grid/FreeSpaceBoundaryTest.cpp; it falls as θ², 1.1e-5 at
///    θ = 0.1), and the interior error is bounded by the boundary's (maximum principle):
///    6× below the discretisation error of a 256³ grid (3e-4), 300× at 32³. Cost O(boundary cells ·
///    log(occupied cells)) instead of the product.
///  - multipole (Multipole.hpp): monopole + quadrupole of all the mass about its centre of
///    mass, when more than kGatherCells cells are occupied (the gather would not scale):
///    error O((a/d)^3) for an aggregate of size a seen from distance d; exact for a sphere.
/// The multipole moments and the occupied-cell count take one all-reduce; the tree adds one
/// all-gather of the occupied cells.
#include "gravity/field/CellLayout.hpp"
#include "gravity/poisson/Multipole.hpp"
#include "gravity/tree/Octree.hpp"

#include <span>
#include <vector>

namespace regolith::gravity {

class FreeSpaceBoundary {
public:
    /// Most occupied cells (all ranks) gathered for the tree; beyond, the multipole.
    static constexpr double kGatherCells = 2.0e6;
    /// Opening angle of the boundary tree.
    static constexpr double kTheta = 0.2;
    /// Most targets sharing one tree walk.
    static constexpr std::size_t kGroupSize = 32;

    /// Computes what evaluate() needs from density component 0. COLLECTIVE over `comm`.
    void update(core::Comm const& comm, CellField const& density, double G);

    /// Potentials [length^2 / time^2] at `points` into `phi` (same size). Consecutive points
    /// share a walk in groups of kGroupSize: pass them in a coherent order (coherentOrder).
    /// Points must lie outside the occupied cells (ghost cells beyond the faces do). Local.
    void evaluate(std::span<core::Vec3 const> points, std::span<double> phi) const;

    [[nodiscard]] bool usesTree() const { return m_useTree; }
    [[nodiscard]] MassMoments const& moments() const { return m_moments; }

    /// A permutation of `cells` that keeps spatial neighbours together (Morton order of the
    /// cell indices, which may be negative by up to 8): the order evaluate() wants.
    [[nodiscard]] static std::vector<std::size_t> coherentOrder(std::span<GlobalCell const> cells);

private:
    MassMoments m_moments;
    double m_G = 0.0;
    bool m_useTree = false;
    tree::Octree m_tree;
};

} // namespace regolith::gravity
