#include "gravity/poisson/PoissonSolver.hpp"

#include "core/Error.hpp"
#include "gravity/poisson/PetscCheck.hpp"

#include <fmt/format.h>
#include <mpi.h>
#include <petscksp.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

namespace regolith::gravity {

using detail::petscCheck;

namespace {

/// Each solver gets its own options prefix, so two solvers (or a solver and the app) never
/// read each other's options from PETSc's global database. Incremented by every rank on
/// every (collective) construction, so it is the same on all ranks.
std::atomic<int> g_solverCount{0};

/// "-ksp_type cg -pc_type gamg" -> "-<prefix>ksp_type cg -<prefix>pc_type gamg": every token
/// that starts with '-' and a letter is an option name; values (also "-1e-3") stay as they
/// are. Appends the prefixed names to `names`.
std::string prefixed(std::string const& options, std::string const& prefix,
                     std::vector<std::string>& names) {
    std::istringstream in(options);
    std::string token;
    std::string out;
    while (in >> token) {
        if (token.size() > 1 && token[0] == '-' &&
            std::isalpha(static_cast<unsigned char>(token[1])) != 0) {
            token = "-" + prefix + token.substr(1);
            names.push_back(token);
        }
        out += token + " ";
    }
    return out;
}

} // namespace

/// A ghost cell beyond a free-space face that a row's stencil reaches.
struct BoundaryTerm {
    PetscInt localRow;
    GlobalCell ghost;
    double weight; ///< 1 / h^2 of the axis
};

struct PoissonSolver::Petsc {
    Mat A = nullptr;
    Vec x = nullptr;
    Vec b = nullptr;
    KSP ksp = nullptr;
    MatNullSpace nullSpace = nullptr;
    std::vector<std::string> optionNames;
    std::vector<BoundaryTerm> boundary;   ///< in FreeSpaceBoundary::coherentOrder of the ghosts
    std::vector<core::Vec3> ghostCentres; ///< centre of each term's ghost
    std::vector<double> ghostPotential;   ///< its potential, per solve

    Petsc() = default;
    Petsc(Petsc const&) = delete;
    Petsc& operator=(Petsc const&) = delete;
    ~Petsc() {
        // Destruction must not throw; a failure here would only leak.
        KSPDestroy(&ksp);
        MatNullSpaceDestroy(&nullSpace);
        VecDestroy(&x);
        VecDestroy(&b);
        MatDestroy(&A);
        for (auto const& name : optionNames)
            PetscOptionsClearValue(nullptr, name.c_str());
    }
};

PoissonSolver::PoissonSolver(core::Comm const& comm, CellLayout const& layout,
                             PoissonOptions options)
    : m_comm(comm.duplicate())
    , m_layout(&layout)
    , m_options(std::move(options))
    , m_petsc(std::make_unique<Petsc>()) {
    auto const& periodic = layout.forest().periodic();
    m_periodic = periodic[0] && periodic[1] && periodic[2];
    if (!m_periodic && (periodic[0] || periodic[1] || periodic[2]))
        throw core::InputError("domain.periodic: grid gravity needs every axis periodic (a "
                               "periodic lattice) or none (free space), not a mix");
    detail::PetscQuiet quiet;
    auto& p = *m_petsc;
    MPI_Comm const raw = m_comm.raw();
    auto const nLocal = static_cast<PetscInt>(layout.localBlockCount() * layout.cellsInBlock());
    // 7 entries per row at most, 6 of which may belong to another rank's block.
    petscCheck(MatCreateAIJ(raw, nLocal, nLocal, PETSC_DETERMINE, PETSC_DETERMINE, 7, nullptr, 6,
                            nullptr, &p.A),
               "MatCreateAIJ");

    auto const& n = layout.cellsPerBlock();
    core::Vec3 const invH2 = layout.spacing().cwiseInverse().cwiseAbs2();
    double const diag = 2.0 * invH2.sum();
    for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
        auto const& o = layout.origin(blk);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    std::array<PetscInt, 7> cols{};
                    std::array<PetscScalar, 7> vals{};
                    GlobalCell const c{o[0] + i, o[1] + j, o[2] + k};
                    auto const row = static_cast<PetscInt>(layout.owner(c)->row);
                    cols[0] = row;
                    vals[0] = diag;
                    int count = 1;
                    for (int a = 0; a < 3; ++a)
                        for (int dir : {-1, 1}) {
                            GlobalCell nb = c;
                            nb[static_cast<std::size_t>(a)] += dir;
                            auto const owner = layout.owner(nb);
                            if (!owner) { // free-space face: value known, moved to the rhs
                                p.boundary.push_back(
                                    {row - static_cast<PetscInt>(layout.rowBegin()), nb, invH2[a]});
                                continue;
                            }
                            cols[static_cast<std::size_t>(count)] =
                                static_cast<PetscInt>(owner->row);
                            vals[static_cast<std::size_t>(count)] = -invH2[a];
                            ++count;
                        }
                    // ADD_VALUES: with one or two cells on a periodic axis the two
                    // neighbours are the same cell (or the cell itself) and must add up.
                    petscCheck(
                        MatSetValues(p.A, 1, &row, count, cols.data(), vals.data(), ADD_VALUES),
                        "MatSetValues");
                }
    }
    {
        std::vector<GlobalCell> ghosts;
        ghosts.reserve(p.boundary.size());
        for (auto const& t : p.boundary)
            ghosts.push_back(t.ghost);
        std::vector<BoundaryTerm> ordered;
        ordered.reserve(p.boundary.size());
        for (std::size_t i : FreeSpaceBoundary::coherentOrder(ghosts)) {
            ordered.push_back(p.boundary[i]);
            p.ghostCentres.push_back(layout.centre(p.boundary[i].ghost));
        }
        p.boundary = std::move(ordered);
        p.ghostPotential.resize(p.boundary.size());
    }
    petscCheck(MatAssemblyBegin(p.A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petscCheck(MatAssemblyEnd(p.A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    if (m_periodic) {
        petscCheck(MatNullSpaceCreate(raw, PETSC_TRUE, 0, nullptr, &p.nullSpace),
                   "MatNullSpaceCreate");
        petscCheck(MatSetNullSpace(p.A, p.nullSpace), "MatSetNullSpace");
    }
    petscCheck(MatCreateVecs(p.A, &p.x, &p.b), "MatCreateVecs");
    petscCheck(VecSet(p.x, 0.0), "VecSet");

    petscCheck(KSPCreate(raw, &p.ksp), "KSPCreate");
    std::string const prefix = fmt::format("regolith_grav{}_", g_solverCount++);
    petscCheck(KSPSetOptionsPrefix(p.ksp, prefix.c_str()), "KSPSetOptionsPrefix");
    petscCheck(KSPSetOperators(p.ksp, p.A, p.A), "KSPSetOperators");
    petscCheck(KSPSetType(p.ksp, KSPCG), "KSPSetType");
    PC pc = nullptr;
    petscCheck(KSPGetPC(p.ksp, &pc), "KSPGetPC");
    petscCheck(PCSetType(pc, PCGAMG), "PCSetType");
    petscCheck(
        KSPSetTolerances(p.ksp, m_options.rtol, 1e-300, PETSC_DEFAULT, m_options.maxIterations),
        "KSPSetTolerances");
    petscCheck(KSPSetNormType(p.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    petscCheck(KSPSetInitialGuessNonzero(p.ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
    std::string const opts = prefixed(m_options.petscOptions, prefix, p.optionNames);
    if (PetscOptionsInsertString(nullptr, opts.c_str()) != 0)
        throw core::InputError("gravity.petsc.options: PETSc cannot parse \"" +
                               m_options.petscOptions + "\"");
    if (PetscErrorCode const e = KSPSetFromOptions(p.ksp); e != 0)
        throw core::InputError("gravity.petsc.options: PETSc rejects \"" + m_options.petscOptions +
                               "\": " + detail::petscMessage(e));
    KSPType kspType = nullptr;
    PCType pcType = nullptr;
    petscCheck(KSPGetType(p.ksp, &kspType), "KSPGetType");
    petscCheck(PCGetType(pc, &pcType), "PCGetType");
    m_solverName = std::string(kspType ? kspType : "?") + " / " + (pcType ? pcType : "?");
}

PoissonSolver::~PoissonSolver() = default;

void PoissonSolver::setRelativeTolerance(double rtol) {
    if (!(rtol > 0.0 && rtol < 1.0))
        throw core::Error(fmt::format("PoissonSolver: relative tolerance {} not in (0, 1)", rtol));
    m_options.rtol = rtol;
    petscCheck(KSPSetTolerances(m_petsc->ksp, rtol, 1e-300, PETSC_DEFAULT, m_options.maxIterations),
               "KSPSetTolerances");
}

void PoissonSolver::resetInitialGuess() {
    petscCheck(VecSet(m_petsc->x, 0.0), "VecSet");
}

SolveStats PoissonSolver::solve(CellField const& density, CellField& potential) {
    detail::PetscQuiet quiet;
    auto& p = *m_petsc;
    auto const& layout = *m_layout;
    double const fourPiG = 4.0 * std::numbers::pi * m_options.G;
    double shift = 0.0; // mean density, periodic only
    if (m_periodic) {
        double const sum = m_comm.allReduce(density.localInteriorSum(), core::ReduceOp::Sum);
        shift = sum / static_cast<double>(layout.globalCellCount());
    } else {
        m_boundary.update(m_comm, density, m_options.G);
        m_boundary.evaluate(p.ghostCentres, p.ghostPotential);
    }
    PetscScalar* b = nullptr;
    petscCheck(VecGetArray(p.b, &b), "VecGetArray");
    std::size_t const cells = layout.cellsInBlock();
    for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
        auto const rho = density.block(blk);
        for (std::size_t c = 0; c < cells; ++c)
            b[blk * cells + c] = -fourPiG * (rho[layout.padOfInterior(c)] - shift);
    }
    for (std::size_t i = 0; i < p.boundary.size(); ++i)
        b[p.boundary[i].localRow] += p.boundary[i].weight * p.ghostPotential[i];
    petscCheck(VecRestoreArray(p.b, &b), "VecRestoreArray");
    if (p.nullSpace)
        petscCheck(MatNullSpaceRemove(p.nullSpace, p.b), "MatNullSpaceRemove");

    SolveStats stats;
    if (!m_setUp) {
        double const t0 = MPI_Wtime();
        petscCheck(KSPSetUp(p.ksp), "KSPSetUp");
        stats.setupSeconds = MPI_Wtime() - t0;
        m_setUp = true;
    }
    double const t0 = MPI_Wtime();
    petscCheck(KSPSolve(p.ksp, p.b, p.x), "KSPSolve");
    stats.solveSeconds = MPI_Wtime() - t0;
    PetscInt its = 0;
    PetscReal rnorm = 0.0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    petscCheck(KSPGetIterationNumber(p.ksp, &its), "KSPGetIterationNumber");
    petscCheck(KSPGetResidualNorm(p.ksp, &rnorm), "KSPGetResidualNorm");
    petscCheck(KSPGetConvergedReason(p.ksp, &reason), "KSPGetConvergedReason");
    stats.iterations = static_cast<int>(its);
    stats.residual = static_cast<double>(rnorm);
    if (reason < 0) {
        petscCheck(VecSet(p.x, 0.0), "VecSet"); // do not warm-start from a diverged iterate
        throw core::Error(fmt::format(
            "grid gravity: the Poisson solve ({}) did not converge: {} after {} iterations, "
            "residual norm {:.3e} (gravity.petsc.options = \"{}\")",
            m_solverName, KSPConvergedReasons[reason], stats.iterations, stats.residual,
            m_options.petscOptions));
    }
    PetscScalar const* x = nullptr;
    petscCheck(VecGetArrayRead(p.x, &x), "VecGetArrayRead");
    for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
        auto phi = potential.block(blk);
        for (std::size_t c = 0; c < cells; ++c)
            phi[layout.padOfInterior(c)] = x[blk * cells + c];
    }
    petscCheck(VecRestoreArrayRead(p.x, &x), "VecRestoreArrayRead");
    return stats;
}

} // namespace regolith::gravity
