#pragma once
/// Every PETSc call of gravity/ sits behind this interface, implemented by a shared module
/// (libregolith_petsc.so, PetscModule.cpp) that is loaded with dlopen the first time a run
/// needs PETSc (PetscSession, i.e. grid gravity solved with PETSc). A run that never solves on
/// the grid then maps none of PETSc's libraries: PETSc, Trilinos, HYPRE, SuperLU, ... are
/// 16 MB of resident pages in every process (docs/notes/memory.md). No PETSc header here.
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace regolith::gravity::petsc {

/// A PETSc call failed (the message names the call and PETSc's own message).
/// `rejectedOptions`: the user's options string was refused, an input error.
struct Failure : std::runtime_error {
    Failure(std::string const& what, bool rejected)
        : std::runtime_error(what)
        , rejectedOptions(rejected) {}
    bool rejectedOptions;
};

/// What one KSPSolve did.
struct SolveResult {
    int iterations = 0;
    double residual = 0.0;
    double setupSeconds = 0.0; ///< KSPSetUp of this call (the first solve only)
    double solveSeconds = 0.0;
    bool converged = false;
    /// Converged before its first iteration with x zero and a non-zero right-hand side
    /// (tolerances that stop the solve at once, e.g. -ksp_rtol 2, from a zero guess).
    bool stoppedAtZero = false;
    std::string reason; ///< KSPConvergedReasons[reason]
    /// The first solve only: the options of finish() that PETSc had not read by then
    /// (misspelt, or for another solver or preconditioner), space-separated; else empty.
    std::string unusedOptions;
};

/// A symmetric sparse system A x = b over the rows of this rank (an AIJ matrix, CG with GAMG
/// by default), assembled once and solved many times from the last solution.
class SparseSystem {
public:
    virtual ~SparseSystem() = default;
    /// Adds `count` entries to global row `row` (ADD_VALUES). Rows of this rank only.
    virtual void addRow(std::int64_t row, int count, std::int64_t const* cols,
                        double const* values) = 0;
    /// Assembles A (with the constant null space if asked), creates x = 0 and b, and the KSP
    /// (cg / gamg, unpreconditioned norm, nonzero initial guess, rtol, maxIterations), then
    /// applies `options` under a prefix of its own. Returns "ksp_type / pc_type".
    virtual std::string finish(bool constantNullSpace, std::string const& options, double rtol,
                               int maxIterations) = 0;
    virtual void setTolerances(double rtol, int maxIterations) = 0;
    /// The next solve starts from zero.
    virtual void zeroSolution() = 0;
    /// b (this rank's rows) in, x out; the null space is removed from b first. A solve that
    /// does not converge leaves x zero (no warm start from a diverged iterate).
    virtual SolveResult solve(double const* b, double* x) = 0;
};

class Module {
public:
    virtual ~Module() = default;
    /// PetscInitialize on MPI_COMM_WORLD unless PETSc is running; true if this call did.
    virtual bool initialize(int& argc, char**& argv) = 0;
    virtual void finalize() = 0;
    [[nodiscard]] virtual bool initialized() = 0;
    [[nodiscard]] virtual std::string version() = 0;
    /// A system with `localRows` rows on this rank, at most 7 entries per row, 6 of them
    /// possibly another rank's. COLLECTIVE over `comm`.
    virtual std::unique_ptr<SparseSystem> sparseSystem(MPI_Comm comm, std::int64_t localRows) = 0;
};

/// The module, loaded on the first call (REGOLITH_PETSC_MODULE, else the build's copy, else
/// ../lib/ beside the executable). Throws core::Error naming the file and the loader's message.
Module& module();

} // namespace regolith::gravity::petsc

/// The module's one exported symbol.
extern "C" regolith::gravity::petsc::Module* regolith_petsc_module();
