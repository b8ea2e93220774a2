// The shared module libregolith_petsc.so (see PetscModule.hpp): the only code that includes
// PETSc. Errors leave as petsc::Failure; the caller turns them into core::Error.
#include "gravity/petsc/PetscModule.hpp"

#include <petscksp.h>

#include <array>
#include <atomic>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace regolith::gravity::petsc {

namespace {

/// PETSc's message for `ierr` (with the specific text of the last error, if any).
std::string message(PetscErrorCode ierr) {
    char const* text = nullptr;
    char* specific = nullptr;
    if (PetscErrorMessage(ierr, &text, &specific) != 0)
        return "(no message)";
    std::string out = text ? text : "";
    if (specific && specific[0] != '\0')
        out += std::string(": ") + specific;
    return out;
}

void check(PetscErrorCode ierr, char const* what) {
    if (ierr != 0)
        throw Failure(std::string("PETSc ") + what + " failed: " + message(ierr), false);
}

/// RAII: PETSc returns error codes without printing its traceback (we report them).
class Quiet {
public:
    Quiet() {
        check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
    }
    ~Quiet() { PetscPopErrorHandler(); }
    Quiet(Quiet const&) = delete;
    Quiet& operator=(Quiet const&) = delete;
};

/// Each system gets its own options prefix, so two systems (or a system and the app) never
/// read each other's options from PETSc's global database. Incremented by every rank on every
/// (collective) construction, so it is the same on all ranks.
std::atomic<int> g_systemCount{0};

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

class PetscSystem final : public SparseSystem {
public:
    PetscSystem(MPI_Comm comm, std::int64_t localRows)
        : m_comm(comm) {
        Quiet quiet;
        auto const n = static_cast<PetscInt>(localRows);
        check(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 7, nullptr, 6, nullptr,
                           &m_A),
              "MatCreateAIJ");
    }
    PetscSystem(PetscSystem const&) = delete;
    PetscSystem& operator=(PetscSystem const&) = delete;
    ~PetscSystem() override {
        // Destruction must not throw; a failure here would only leak.
        KSPDestroy(&m_ksp);
        MatNullSpaceDestroy(&m_nullSpace);
        VecDestroy(&m_x);
        VecDestroy(&m_b);
        MatDestroy(&m_A);
        for (auto const& name : m_optionNames)
            PetscOptionsClearValue(nullptr, name.c_str());
    }

    void addRow(std::int64_t row, int count, std::int64_t const* cols,
                double const* values) override {
        Quiet quiet;
        PetscInt const r = static_cast<PetscInt>(row);
        std::array<PetscInt, 7> c{};
        std::array<PetscScalar, 7> v{};
        if (count < 0 || count > 7)
            throw Failure("PETSc system: a row of " + std::to_string(count) + " entries", false);
        for (int k = 0; k < count; ++k) {
            c[static_cast<std::size_t>(k)] = static_cast<PetscInt>(cols[k]);
            v[static_cast<std::size_t>(k)] = values[k];
        }
        check(MatSetValues(m_A, 1, &r, count, c.data(), v.data(), ADD_VALUES), "MatSetValues");
    }

    std::string finish(bool constantNullSpace, std::string const& options, double rtol,
                       int maxIterations) override {
        Quiet quiet;
        check(MatAssemblyBegin(m_A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
        check(MatAssemblyEnd(m_A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
        if (constantNullSpace) {
            check(MatNullSpaceCreate(m_comm, PETSC_TRUE, 0, nullptr, &m_nullSpace),
                  "MatNullSpaceCreate");
            check(MatSetNullSpace(m_A, m_nullSpace), "MatSetNullSpace");
        }
        check(MatCreateVecs(m_A, &m_x, &m_b), "MatCreateVecs");
        check(VecSet(m_x, 0.0), "VecSet");

        check(KSPCreate(m_comm, &m_ksp), "KSPCreate");
        std::string const prefix = "regolith_grav" + std::to_string(g_systemCount++) + "_";
        m_prefix = prefix;
        check(KSPSetOptionsPrefix(m_ksp, prefix.c_str()), "KSPSetOptionsPrefix");
        check(KSPSetOperators(m_ksp, m_A, m_A), "KSPSetOperators");
        check(KSPSetType(m_ksp, KSPCG), "KSPSetType");
        PC pc = nullptr;
        check(KSPGetPC(m_ksp, &pc), "KSPGetPC");
        check(PCSetType(pc, PCGAMG), "PCSetType");
        setTolerances(rtol, maxIterations);
        check(KSPSetNormType(m_ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
        check(KSPSetInitialGuessNonzero(m_ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
        std::string const opts = prefixed(options, prefix, m_optionNames);
        if (PetscOptionsInsertString(nullptr, opts.c_str()) != 0)
            throw Failure("PETSc cannot parse \"" + options + "\"", true);
        if (PetscErrorCode const e = KSPSetFromOptions(m_ksp); e != 0)
            throw Failure("PETSc rejects \"" + options + "\": " + message(e), true);
        KSPType kspType = nullptr;
        PCType pcType = nullptr;
        check(KSPGetType(m_ksp, &kspType), "KSPGetType");
        check(PCGetType(pc, &pcType), "PCGetType");
        return std::string(kspType ? kspType : "?") + " / " + (pcType ? pcType : "?");
    }

    void setTolerances(double rtol, int maxIterations) override {
        check(KSPSetTolerances(m_ksp, rtol, 1e-300, PETSC_DEFAULT, maxIterations),
              "KSPSetTolerances");
    }

    void zeroSolution() override { check(VecSet(m_x, 0.0), "VecSet"); }

    SolveResult solve(double const* b, double* x) override {
        Quiet quiet;
        PetscInt n = 0;
        check(VecGetLocalSize(m_b, &n), "VecGetLocalSize");
        PetscScalar* bp = nullptr;
        check(VecGetArray(m_b, &bp), "VecGetArray");
        for (PetscInt i = 0; i < n; ++i)
            bp[i] = b[i];
        check(VecRestoreArray(m_b, &bp), "VecRestoreArray");
        if (m_nullSpace)
            check(MatNullSpaceRemove(m_nullSpace, m_b), "MatNullSpaceRemove");

        SolveResult r;
        if (!m_setUp) {
            double const t0 = MPI_Wtime();
            check(KSPSetUp(m_ksp), "KSPSetUp");
            r.setupSeconds = MPI_Wtime() - t0;
            m_setUp = true;
        }
        double const t0 = MPI_Wtime();
        // With -ksp_error_if_not_converged a divergence is an error code, not a reason: it is
        // reported as the reason (the same on every rank), so that the caller's collective
        // "did not converge" applies; any other error is a failure.
        if (PetscErrorCode const ierr = KSPSolve(m_ksp, m_b, m_x); ierr != 0) {
            KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
            if (KSPGetConvergedReason(m_ksp, &reason) != 0 || reason >= 0)
                check(ierr, "KSPSolve");
        }
        r.solveSeconds = MPI_Wtime() - t0;
        if (!m_checkedUse) {
            // Every option is read by now (KSPSetFromOptions, the set-up, the first solve).
            m_checkedUse = true;
            for (auto const& name : m_optionNames) {
                PetscBool used = PETSC_FALSE;
                // The database keeps names without the leading '-'.
                check(PetscOptionsUsed(nullptr, name.c_str() + 1, &used), "PetscOptionsUsed");
                if (!used)
                    r.unusedOptions +=
                        (r.unusedOptions.empty() ? "-" : " -") + name.substr(m_prefix.size() + 1);
            }
        }
        PetscInt its = 0;
        PetscReal rnorm = 0.0;
        KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
        check(KSPGetIterationNumber(m_ksp, &its), "KSPGetIterationNumber");
        check(KSPGetResidualNorm(m_ksp, &rnorm), "KSPGetResidualNorm");
        check(KSPGetConvergedReason(m_ksp, &reason), "KSPGetConvergedReason");
        r.iterations = static_cast<int>(its);
        r.residual = static_cast<double>(rnorm);
        r.converged = reason > 0;
        r.reason = KSPConvergedReasons[reason];
        // What the solve returned, not what it started from (PETSc may replace the initial
        // guess, -ksp_guess_type): reason and its are the same on every rank (collective).
        if (r.converged && its == 0) {
            PetscReal xnorm = 0.0, bnorm = 0.0;
            check(VecNorm(m_x, NORM_2, &xnorm), "VecNorm");
            check(VecNorm(m_b, NORM_2, &bnorm), "VecNorm");
            r.stoppedAtZero = xnorm == 0.0 && bnorm > 0.0;
        }
        if (!r.converged)
            zeroSolution(); // do not warm-start from a diverged iterate
        PetscScalar const* xp = nullptr;
        check(VecGetArrayRead(m_x, &xp), "VecGetArrayRead");
        for (PetscInt i = 0; i < n; ++i)
            x[i] = xp[i];
        check(VecRestoreArrayRead(m_x, &xp), "VecRestoreArrayRead");
        return r;
    }

private:
    MPI_Comm m_comm;
    Mat m_A = nullptr;
    Vec m_x = nullptr;
    Vec m_b = nullptr;
    KSP m_ksp = nullptr;
    MatNullSpace m_nullSpace = nullptr;
    bool m_setUp = false;
    bool m_checkedUse = false; ///< unusedOptions reported (first solve)
    std::string m_prefix;
    std::vector<std::string> m_optionNames;
};

class PetscLibrary final : public Module {
public:
    bool initialize(int& argc, char**& argv) override {
        if (initialized())
            return false;
        if (PetscErrorCode const e = PetscInitialize(&argc, &argv, nullptr, nullptr); e != 0)
            throw Failure("PetscInitialize failed with error code " + std::to_string(e), false);
        return true;
    }
    void finalize() override { PetscFinalize(); }
    bool initialized() override {
        PetscBool on = PETSC_FALSE;
        PetscInitialized(&on);
        return on == PETSC_TRUE;
    }
    std::string version() override {
        char text[256] = {};
        PetscGetVersion(text, sizeof text);
        return text;
    }
    std::unique_ptr<SparseSystem> sparseSystem(MPI_Comm comm, std::int64_t localRows) override {
        return std::make_unique<PetscSystem>(comm, localRows);
    }
};

} // namespace

} // namespace regolith::gravity::petsc

extern "C" regolith::gravity::petsc::Module* regolith_petsc_module() {
    static regolith::gravity::petsc::PetscLibrary library;
    return &library;
}
