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
///
/// Kernel. Newton's -G m / r suits a solve that convolves with it (FftFreeSpace). A solve of
/// the 7-point Laplacian (PoissonSolver) follows the lattice's own Green's function instead,
/// which differs from 1/r by ~h² / (4 r³) (LatticeGreensFunction.hpp): with Newton's values a
/// grain 2.5 cells from a face felt 6e-3 of a neighbour's pull 4 cells away from its own field
/// (docs/notes/grid-gravity.md). With BoundaryKernel::Lattice the
/// occupied cells within kLatticeRadius cells of a ghost (per axis) contribute the lattice
/// kernel's value, so the solve reproduces the infinite lattice's solution up to the far
/// cells' ~h² / (4 r³) (r > kLatticeRadius cells) and the tree's error. Those cells (all
/// ranks') take one more all-gather: nothing while the mass stays kLatticeRadius cells from
/// the faces, all of it on a grid that small.
#include "gravity/field/CellLayout.hpp"
#include "gravity/poisson/LatticeGreensFunction.hpp"
#include "gravity/poisson/Multipole.hpp"
#include "gravity/tree/Octree.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace regolith::gravity {

/// The field the boundary values are those of (see the class comment).
enum class BoundaryKernel {
    Newton,  ///< -G m / r: the continuous field (FFT convolution)
    Lattice, ///< the 7-point Laplacian's own field near the mass, Newton's beyond
};

class FreeSpaceBoundary {
public:
    /// Most occupied cells (all ranks) gathered for the tree; beyond, the multipole.
    static constexpr double kGatherCells = 2.0e6;
    /// Opening angle of the boundary tree.
    static constexpr double kTheta = 0.2;
    /// Most targets sharing one tree walk.
    static constexpr std::size_t kGroupSize = 32;
    /// Cells per axis within which BoundaryKernel::Lattice takes the lattice's kernel; beyond,
    /// Newton's is off by < 3.5e-4 / h per unit mass (3e-3 of it). Each ghost with mass near
    /// its face sums over (2R + 1)² R cells: 2.3e3 at 8 (the boundary of a 64³ grid filled
    /// with mass: 0.04 s; 0.28 s with radius 12 and a sparse look-up).
    static constexpr int kLatticeRadius = 8;

    explicit FreeSpaceBoundary(BoundaryKernel kernel = BoundaryKernel::Newton)
        : m_kernel(kernel) {}

    /// Computes what evaluate() needs from density component 0. COLLECTIVE over `comm`.
    void update(core::Comm const& comm, CellField const& density, double G);

    /// Potentials [length^2 / time^2] at `points` into `phi` (same size). Consecutive points
    /// share a walk in groups of kGroupSize: pass them in a coherent order (coherentOrder).
    /// Points must lie outside the occupied cells (ghost cells beyond the faces do); with
    /// BoundaryKernel::Lattice they must be centres of cells of the density's layout. Local.
    void evaluate(std::span<core::Vec3 const> points, std::span<double> phi) const;

    [[nodiscard]] bool usesTree() const { return m_useTree; }
    [[nodiscard]] MassMoments const& moments() const { return m_moments; }

    /// A permutation of `cells` that keeps spatial neighbours together (Morton order of the
    /// cell indices, which may be negative by up to 8): the order evaluate() wants.
    [[nodiscard]] static std::vector<std::size_t> coherentOrder(std::span<GlobalCell const> cells);

private:
    /// Gathers the occupied cells (all ranks) within kLatticeRadius of a free-space face into
    /// that face's slab, and tabulates the lattice kernel. COLLECTIVE.
    void gatherNearCells(core::Comm const& comm, CellLayout const& layout,
                         std::span<double const> mine);
    void evaluateTree(std::span<core::Vec3 const> points, std::span<double> phi) const;
    /// phi[i] += -G Σ m (K - 1/r) over the near cells within kLatticeRadius of points[i].
    void addLatticeCorrections(std::span<core::Vec3 const> points, std::span<double> phi) const;
    [[nodiscard]] std::array<std::int64_t, 3> cellOf(core::Vec3 const& x) const;

    BoundaryKernel m_kernel;
    MassMoments m_moments;
    double m_G = 0.0;
    bool m_useTree = false;
    tree::Octree m_tree;
    std::optional<LatticeGreensFunction> m_lattice; ///< for the last layout's spacing
    core::Vec3 m_firstCentre = core::Vec3::Zero();  ///< centre of global cell (0, 0, 0)
    std::array<std::int64_t, 3> m_cells{};          ///< global cells per axis
    /// Per face (axis a: 2a for the low side, 2a + 1 for the high), the mass of the occupied
    /// cells less than kLatticeRadius cells deep, dense by [depth][b][c] (b, c the other two
    /// axes in cyclic order); empty for a face without such cells. Every cell within
    /// kLatticeRadius of a ghost beyond that face is in it.
    std::array<std::vector<double>, 6> m_slab;
};

} // namespace regolith::gravity
