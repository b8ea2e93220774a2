#pragma once
/// The Poisson solve  ∇²φ = 4πGρ  on the cells of a CellLayout with PETSc (through the
/// PETSc module, gravity/petsc/PetscModule.hpp: no PETSc header in gravity/ outside it).
/// Second-order 7-point Laplacian on cell centres, assembled ONCE as -∇² (symmetric positive
/// (semi-)definite, so CG applies) with rows numbered block by block along the forest's
/// curve: PETSc's row distribution is the forest's. The KSP is built once from a run-time options
/// string, its set-up (e.g. the GAMG hierarchy) reused by every solve, and each solve starts from
/// the previous potential.
///
/// Boundaries: all axes periodic -> periodic Laplacian with the constant null space, mean
/// density subtracted; no axis periodic -> free space: the potential at the centres of the
/// ghost cells beyond each domain face (FreeSpaceBoundary.hpp: a tree over the occupied
/// cells, or a multipole expansion), folded into the right-hand side. Mixed periodicity is refused.
#include "core/mpi/Comm.hpp"
#include "gravity/field/CellField.hpp"
#include "gravity/poisson/FreeSpaceBoundary.hpp"

#include <memory>
#include <string>

namespace regolith::gravity {

struct PoissonOptions {
    double G = 6.674e-11; ///< gravitational constant [length^3 / (mass time^2)]
    /// PETSc options (scene key gravity.petsc.options), e.g. "-ksp_type cg -pc_type gamg";
    /// applied after the defaults below, so they override them. Empty: the defaults.
    std::string petscOptions;
    double rtol = 1e-10;       ///< default relative tolerance (unpreconditioned residual)
    int maxIterations = 10000; ///< default iteration limit
    /// sync.reproducible: every solve starts from a zero potential instead of the last
    /// solution (the warm start), and the default preconditioner is block Jacobi instead of
    /// GAMG, whose aggregation gave other bits from run to run on 3 or more ranks; the result
    /// then depends on the density and the layout only, so a restarted run, which has no last
    /// solution, repeats the bits of the run it continues. `petscOptions` still apply last.
    bool reproducible = false;
};

/// What one solve did.
struct SolveStats {
    int iterations = 0;
    double residual = 0.0;     ///< final residual norm as PETSc reports it
    double setupSeconds = 0.0; ///< KSPSetUp time of this call (non-zero on the first solve)
    double solveSeconds = 0.0; ///< KSPSolve time
};

class PoissonSolver {
public:
    /// Assembles the matrix and configures the KSP ("-ksp_type cg -pc_type gamg" by default,
    /// then `options.petscOptions`). Throws core::InputError on every rank for mixed
    /// periodicity ("domain.periodic") or an options string PETSc rejects, e.g. an unknown
    /// solver ("gravity.petsc.options"). Pre: PETSc initialised (PetscSession), `layout`
    /// outlives this object. COLLECTIVE over `comm`.
    PoissonSolver(core::Comm const& comm, CellLayout const& layout, PoissonOptions options);
    ~PoissonSolver();
    PoissonSolver(PoissonSolver const&) = delete;
    PoissonSolver& operator=(PoissonSolver const&) = delete;

    /// Solves for φ [length^2 / time^2] from density component 0 [mass / length^3] (interior
    /// cells) and writes φ into the interior cells of `potential`. Starts from the previous
    /// solution (zero at first). Throws core::InputError on every rank if the solve does not
    /// converge, naming iterations, residual and PETSc's reason. COLLECTIVE.
    SolveStats solve(CellField const& density, CellField& potential);

    /// The next solve starts from zero (a cold start; e.g. after a jump of the mass). Local.
    void resetInitialGuess();
    /// Sets the relative tolerance of the next solves (unpreconditioned residual relative to
    /// |b|; overrides options.rtol and any -ksp_rtol), keeping the set-up. Pre: rtol in
    /// (0, 1). COLLECTIVE in spirit (PETSc state): call on every rank alike.
    void setRelativeTolerance(double rtol);

    /// Free space: the boundary potential of the last solve's density (for boundary ghosts).
    [[nodiscard]] FreeSpaceBoundary const& boundary() const { return m_boundary; }
    [[nodiscard]] bool periodic() const { return m_periodic; }
    [[nodiscard]] double G() const { return m_options.G; }
    /// "ksp_type / pc_type" actually in use, e.g. "cg / gamg".
    [[nodiscard]] std::string const& solverName() const { return m_solverName; }

private:
    struct Petsc; // the module's system, the boundary terms, b and x
    core::Comm m_comm;
    CellLayout const* m_layout;
    PoissonOptions m_options;
    bool m_periodic = false;
    FreeSpaceBoundary m_boundary{BoundaryKernel::Lattice}; ///< the 7-point stencil's own field
    std::string m_solverName;
    std::unique_ptr<Petsc> m_petsc;
};

} // namespace regolith::gravity
