#pragma once
/// Grid-field (particle-mesh) self-gravity on the block forest: deposit grain mass, solve
/// ∇²φ = 4πGρ with PETSc (or, on a free-space domain, the FFT convolution of FftFreeSpace:
/// faster on small uniform grids, serial on rank 0), g = -∇φ on cells, interpolate g to grains with
/// the deposition kernel. Owns the cell layout, the fields, the ghost-exchange plan and the solver,
/// all built once per forest.
///
/// Accuracy: the mesh force is softened over ~2 cells (the kernel width): pairs closer than
/// ~2 h get far too little force (the tests assert this); from ~4 h on the force follows
/// 1/r^2 to about 1 %. A grain's self-force is zero up to the boundary's asymmetry.
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/PoissonMethod.hpp"
#include "gravity/fft/FftFreeSpace.hpp"
#include "gravity/field/GhostExchange.hpp"
#include "gravity/field/GridFieldsView.hpp"
#include "gravity/poisson/PoissonSolver.hpp"
#include "gravity/transfer/MeshTransfer.hpp"

#include <memory>
#include <span>

namespace regolith::gravity {

struct GridGravityOptions {
    PoissonMethod poissonMethod = PoissonMethod::Petsc;
    Assignment assignment = Assignment::Tsc; ///< deposition / interpolation kernel
    int gradientOrder = 2;                   ///< 2 or 4 (gravity.gradient_order)
    PoissonOptions poisson;                  ///< G, PETSc options, tolerances
};

class GridGravity {
public:
    /// Throws core::InputError on every rank for bad options ("gravity.G",
    /// "gravity.gradient_order", "gravity.petsc.options"), a refined forest, bad
    /// cellsPerBlock or mixed periodicity (see CellLayout, PoissonSolver). Pre: PETSc
    /// initialised, `forest` outlives this object. COLLECTIVE over `comm`.
    GridGravity(core::Comm const& comm, domain::BlockForest const& forest,
                std::array<int, 3> cellsPerBlock, GridGravityOptions options);

    /// Deposits `grains` (this rank's share) and computes φ and g on the cells. Throws
    /// core::InputError on every rank for mass outside the domain (MeshTransfer::deposit) and
    /// core::InputError (alike on every rank) for a solve that does not converge. COLLECTIVE.
    SolveStats update(Grains const& grains);
    /// As update(), from density() as the caller filled it (interior cells). COLLECTIVE.
    SolveStats solveFromDensity();

    /// Acceleration [length / time^2] at each grain (mass not used), interpolated with the
    /// deposition kernel and ball samples. Pre: out.size() == grains.position.size(), a
    /// previous update(). COLLECTIVE.
    void accelerations(Grains const& grains, std::span<core::Vec3> out);
    /// ½ Σ m φ over all ranks' grains [mass length^2 / time^2], φ interpolated like g
    /// (includes each grain's mesh-softened self-energy). COLLECTIVE.
    [[nodiscard]] double potentialEnergy(Grains const& grains);

    /// The next PETSc solve starts from a zero potential instead of the last one (after
    /// solves of another problem, e.g. P3M's calibration sources, whose potential would be
    /// a start many times farther from the answer than zero). Not collective.
    void resetInitialGuess();

    [[nodiscard]] CellLayout const& layout() const { return m_layout; }
    [[nodiscard]] CellField& density() { return m_density; }
    [[nodiscard]] CellField const& potential() const { return m_potential; }
    [[nodiscard]] CellField const& acceleration() const { return m_acceleration; }
    [[nodiscard]] double G() const { return m_options.poisson.G; }
    [[nodiscard]] Assignment assignment() const { return m_options.assignment; }
    [[nodiscard]] bool periodic() const { return m_periodic; }
    /// The fields of the last update ("density" [mass / length^3], "potential" [length^2 /
    /// time^2], "acceleration" g = -∇φ [length / time^2]), read-only; valid
    /// while this object lives. Not collective.
    [[nodiscard]] GridFieldsView fields() const {
        return {&m_layout,
                {{"density", &m_density},
                 {"potential", &m_potential},
                 {"acceleration", &m_acceleration}}};
    }

private:
    /// The ghost cells beyond free-space faces (block, padded index, centre), in
    /// FreeSpaceBoundary::coherentOrder; empty for a periodic domain.
    void listBoundaryGhosts();
    /// Sets those ghost cells to the free-space potential of the last update.
    void fillBoundaryGhosts();

    core::Comm m_comm;
    GridGravityOptions m_options;
    CellLayout m_layout;
    GhostExchange m_ghosts;
    MeshTransfer m_transfer;
    bool m_periodic = false;
    std::unique_ptr<PoissonSolver> m_solver; ///< PoissonMethod::Petsc
    std::unique_ptr<FftFreeSpace> m_fft;     ///< PoissonMethod::Fft
    FreeSpaceBoundary m_boundary;            ///< the ghosts' values with the FFT
    CellField m_density;
    CellField m_potential;
    CellField m_acceleration;
    std::vector<std::pair<std::size_t, std::size_t>> m_boundaryGhosts; ///< (block, padded)
    std::vector<core::Vec3> m_boundaryCentres;
    std::vector<double> m_boundaryPotential;
};

} // namespace regolith::gravity
