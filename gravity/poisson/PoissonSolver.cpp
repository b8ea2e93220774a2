#include "gravity/poisson/PoissonSolver.hpp"

#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "gravity/petsc/PetscModule.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace regolith::gravity {

/// A ghost cell beyond a free-space face that a row's stencil reaches.
struct BoundaryTerm {
    std::size_t localRow;
    GlobalCell ghost;
    double weight; ///< 1 / h^2 of the axis
};

struct PoissonSolver::Petsc {
    std::unique_ptr<petsc::SparseSystem> system;
    std::vector<BoundaryTerm> boundary;   ///< in FreeSpaceBoundary::coherentOrder of the ghosts
    std::vector<core::Vec3> ghostCentres; ///< centre of each term's ghost
    std::vector<double> ghostPotential;   ///< its potential, per solve
    std::vector<double> b, x;             ///< right-hand side and solution, this rank's rows
};

namespace {

/// A PETSc failure as the error the module reports: an input error if the user's options
/// were refused, otherwise a runtime error.
[[noreturn]] void rethrow(petsc::Failure const& e, std::string const& options) {
    if (e.rejectedOptions)
        throw core::InputError(std::string("gravity.petsc.options: ") + e.what());
    throw core::Error(std::string(e.what()) +
                      (options.empty() ? "" : " (gravity.petsc.options = \"" + options + "\")"));
}

} // namespace

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
    auto& p = *m_petsc;
    std::size_t const nLocal = layout.localBlockCount() * layout.cellsInBlock();
    try {
        p.system = petsc::module().sparseSystem(m_comm.raw(), static_cast<std::int64_t>(nLocal));
        auto const& n = layout.cellsPerBlock();
        core::Vec3 const invH2 = layout.spacing().cwiseInverse().cwiseAbs2();
        double const diag = 2.0 * invH2.sum();
        for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
            auto const& o = layout.origin(blk);
            for (int k = 0; k < n[2]; ++k)
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i) {
                        std::array<std::int64_t, 7> cols{};
                        std::array<double, 7> vals{};
                        GlobalCell const c{o[0] + i, o[1] + j, o[2] + k};
                        auto const row = static_cast<std::int64_t>(layout.owner(c)->row);
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
                                        {static_cast<std::size_t>(row) - layout.rowBegin(), nb,
                                         invH2[a]});
                                    continue;
                                }
                                cols[static_cast<std::size_t>(count)] =
                                    static_cast<std::int64_t>(owner->row);
                                vals[static_cast<std::size_t>(count)] = -invH2[a];
                                ++count;
                            }
                        // Added, not set: with one or two cells on a periodic axis the two
                        // neighbours are the same cell (or the cell itself) and must add up.
                        p.system->addRow(row, count, cols.data(), vals.data());
                    }
        }
        std::string const petscOptions = m_options.reproducible
                                             ? "-pc_type bjacobi " + m_options.petscOptions
                                             : m_options.petscOptions;
        m_solverName =
            p.system->finish(m_periodic, petscOptions, m_options.rtol, m_options.maxIterations);
    } catch (petsc::Failure const& e) {
        rethrow(e, m_options.petscOptions);
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
    p.b.resize(nLocal);
    p.x.resize(nLocal);
}

PoissonSolver::~PoissonSolver() = default;

void PoissonSolver::setRelativeTolerance(double rtol) {
    if (!(rtol > 0.0 && rtol < 1.0))
        throw core::Error(fmt::format("PoissonSolver: relative tolerance {} not in (0, 1)", rtol));
    m_options.rtol = rtol;
    try {
        m_petsc->system->setTolerances(rtol, m_options.maxIterations);
    } catch (petsc::Failure const& e) {
        rethrow(e, m_options.petscOptions);
    }
}

void PoissonSolver::resetInitialGuess() {
    try {
        m_petsc->system->zeroSolution();
    } catch (petsc::Failure const& e) {
        rethrow(e, m_options.petscOptions);
    }
}

SolveStats PoissonSolver::solve(CellField const& density, CellField& potential) {
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
    std::size_t const cells = layout.cellsInBlock();
    for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
        auto const rho = density.block(blk);
        for (std::size_t c = 0; c < cells; ++c)
            p.b[blk * cells + c] = -fourPiG * (rho[layout.padOfInterior(c)] - shift);
    }
    for (std::size_t i = 0; i < p.boundary.size(); ++i)
        p.b[p.boundary[i].localRow] += p.boundary[i].weight * p.ghostPotential[i];

    petsc::SolveResult r;
    try {
        if (m_options.reproducible)
            p.system->zeroSolution();
        r = p.system->solve(p.b.data(), p.x.data());
    } catch (petsc::Failure const& e) {
        rethrow(e, m_options.petscOptions);
    }
    // The same on every rank (the options and the solver are); a misspelt option would
    // otherwise be ignored without a word.
    if (!r.unusedOptions.empty())
        core::log::warn("gravity.petsc.options: PETSc did not use {} (misspelt, or for another "
                        "solver or preconditioner than {})",
                        r.unusedOptions, m_solverName);
    SolveStats stats;
    stats.iterations = r.iterations;
    stats.residual = r.residual;
    stats.setupSeconds = r.setupSeconds;
    stats.solveSeconds = r.solveSeconds;
    // KSP's converged reason is the same on every rank: an error every rank agrees on, caused
    // by the options, tolerances or grid the scene chose.
    if (!r.converged)
        throw core::InputError(fmt::format(
            "grid gravity: the Poisson solve ({}) did not converge: {} after {} iterations, "
            "residual norm {:.3e} (gravity.petsc.options = \"{}\")",
            m_solverName, r.reason, stats.iterations, stats.residual, m_options.petscOptions));
    if (r.stoppedAtZero)
        throw core::InputError(fmt::format(
            "grid gravity: the Poisson solve ({}) stopped before its first iteration ({}) from a "
            "zero initial guess, which would make the field zero: gravity.petsc.options = "
            "\"{}\" sets tolerances that stop it at once",
            m_solverName, r.reason, m_options.petscOptions));
    for (std::size_t blk = 0; blk < layout.localBlockCount(); ++blk) {
        auto phi = potential.block(blk);
        for (std::size_t c = 0; c < cells; ++c)
            phi[layout.padOfInterior(c)] = p.x[blk * cells + c];
    }
    return stats;
}

} // namespace regolith::gravity
