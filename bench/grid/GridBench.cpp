// Grid-gravity benchmark (not a test): for the free-space Poisson solve on N^3 cells, the
// set-up time (matrix assembly + KSP creation, then KSPSetUp: the AMG hierarchy) against the
// solve time and iterations, per preconditioner, and cold versus warm start for a mass that
// moves slowly between solves. Prints a table and writes CSV.
//
//   mpiexec -n 2 build/default/bin/grid_bench [--min-cells 32] [--max-cells 128] [--rtol 1e-8]
//       [--csv out.csv]
#include "core/Error.hpp"
#include "gravity/fft/FftFreeSpace.hpp"
#include "gravity/field/CellLayout.hpp"
#include "gravity/petsc/PetscSession.hpp"
#include "gravity/poisson/PoissonSolver.hpp"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench/common/BenchOptions.hpp"

using namespace regolith;
using namespace regolith::gravity;

namespace {

struct Args {
    int maxCells = 128;
    int minCells = 32;
    double rtol = 1e-8;
    std::string csv = "bench/out/grid_bench.csv";
};

Args parse(bench::BenchOptions const& cli) {
    Args a;
    for (auto const& [key, value] : cli.pairs) {
        if (key == "--max-cells")
            a.maxCells = std::atoi(value.c_str());
        else if (key == "--min-cells")
            a.minCells = std::atoi(value.c_str());
        else if (key == "--rtol")
            a.rtol = std::atof(value.c_str());
        else if (key == "--csv")
            a.csv = value;
    }
    return a;
}

/// Two smooth balls, density (1 - r²/R²)² inside radius R (R = 0.5 and 0.2 in the box
/// [-2, 2]^3, the small one off centre), shifted by `shift` along x. Smooth, so a shift of a
/// fraction of a cell changes the density a little (a uniform ball sampled at cell centres
/// would not change at all until a centre crosses its surface).
void fillDensity(CellField& rho, double shift) {
    auto const& layout = rho.layout();
    auto const& n = layout.cellsPerBlock();
    rho.fill(0.0);
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    auto const& o = layout.origin(b);
                    core::Vec3 x = layout.centre({o[0] + i, o[1] + j, o[2] + k});
                    x[0] -= shift;
                    auto bump = [](double r, double R) {
                        double const u = 1.0 - r * r / (R * R);
                        return r < R ? u * u : 0.0;
                    };
                    rho.at(b, i, j, k) =
                        bump(x.norm(), 0.5) + bump((x - core::Vec3{0.6, 0.3, 0.0}).norm(), 0.2);
                }
}

int blocksPerAxis(int cells) {
    return cells >= 64 ? 4 : 2; // blocks of 16-32 cells per axis
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    int noArgs = 0;
    char** noArgv = nullptr;
    PetscSession petsc(noArgs, noArgv);
    core::Comm world;
    bench::BenchOptions const cli = bench::parseBenchOptions(
        argc, argv, "grid_bench", {"--max-cells", "--min-cells", "--rtol", "--csv"},
        world.rank() == 0);
    if (cli.exitCode >= 0)
        return cli.exitCode;
    Args const args = parse(cli);
    std::vector<std::pair<std::string, std::string>> const solvers{
        {"cg+gamg", "-ksp_type cg -pc_type gamg"},
        {"cg+hypre", "-ksp_type cg -pc_type hypre -pc_hypre_type boomeramg"},
    };
    std::ofstream csv;
    if (world.rank() == 0) {
        csv.open(args.csv);
        csv << "ranks,cells,unknowns,solver,assemble_s,setup_s,solve_s,iterations,"
               "solve_s_per_unknown,shift_h,cold_iterations,warm_iterations,cold_solve_s,"
               "warm_solve_s\n";
        std::printf("ranks %d, rtol %.0e, free space [-2,2]^3, blocks 2^3 (<=32^3) or 4^3\n",
                    world.size(), args.rtol);
        std::printf("%-9s %6s %10s %9s %9s %9s %5s %10s | warm start for shifts (h): cold/warm "
                    "iterations\n",
                    "solver", "cells", "unknowns", "assemble", "setup", "solve", "its",
                    "s/unknown");
    }
    for (int cells = args.minCells; cells <= args.maxCells; cells *= 2) {
        domain::ForestSpec spec;
        spec.domain = core::AABB{core::Vec3::Constant(-2.0), core::Vec3::Constant(2.0)};
        int const bpa = blocksPerAxis(cells);
        spec.rootBlocks = {bpa, bpa, bpa};
        spec.cellsPerBlock = {cells / bpa, cells / bpa, cells / bpa};
        domain::BlockForest forest(world, spec);
        CellLayout layout(world, forest, spec.cellsPerBlock, 1);
        CellField reference(layout); // the CG+GAMG potential at rtol, for the FFT comparison
        for (auto const& [name, options] : solvers) {
            PoissonOptions po;
            po.G = 1.0;
            po.rtol = args.rtol;
            po.petscOptions = options;
            world.barrier();
            double const t0 = MPI_Wtime();
            std::unique_ptr<PoissonSolver> solver;
            try {
                solver = std::make_unique<PoissonSolver>(world, layout, po);
            } catch (core::InputError const& e) {
                if (world.rank() == 0)
                    std::printf("%-9s %6d: not available (%s)\n", name.c_str(), cells, e.what());
                continue;
            }
            double const assemble = world.allReduce(MPI_Wtime() - t0, core::ReduceOp::Max);
            CellField rho(layout);
            CellField phi(layout);
            fillDensity(rho, 0.0);
            SolveStats const first = solver->solve(rho, phi);
            // Cold solve with the set-up reused: the steady-state cost of one solve.
            solver->resetInitialGuess();
            SolveStats const cold = solver->solve(rho, phi);
            if (name == "cg+gamg")
                reference = phi;
            double const unknowns = static_cast<double>(layout.globalCellCount());
            double const setup = world.allReduce(first.setupSeconds, core::ReduceOp::Max);
            double const solve = world.allReduce(cold.solveSeconds, core::ReduceOp::Max);
            if (world.rank() == 0)
                std::printf("%-9s %6d %10.0f %9.3f %9.3f %9.3f %5d %10.2e |", name.c_str(), cells,
                            unknowns, assemble, setup, solve, cold.iterations, solve / unknowns);
            double const h = layout.spacing()[0];
            for (double shiftH : {0.01, 0.05, 0.25}) {
                // From the solution at shift 0: warm = previous potential, cold = zero.
                fillDensity(rho, 0.0);
                solver->solve(rho, phi);
                fillDensity(rho, shiftH * h);
                SolveStats const warm = solver->solve(rho, phi);
                solver->resetInitialGuess();
                SolveStats const c = solver->solve(rho, phi);
                double const warmS = world.allReduce(warm.solveSeconds, core::ReduceOp::Max);
                double const coldS = world.allReduce(c.solveSeconds, core::ReduceOp::Max);
                if (world.rank() == 0) {
                    std::printf(" %.2f: %d/%d", shiftH, c.iterations, warm.iterations);
                    csv << world.size() << "," << cells << "," << unknowns << "," << name << ","
                        << assemble << "," << setup << "," << solve << "," << cold.iterations << ","
                        << solve / unknowns << "," << shiftH << "," << c.iterations << ","
                        << warm.iterations << "," << coldS << "," << warmS << "\n";
                }
            }
            if (world.rank() == 0) {
                std::printf("\n");
                std::fflush(stdout);
            }
        }
        // The FFT reference (rank 0 does the transforms; gather and scatter included).
        CellField rho(layout);
        CellField phi(layout);
        fillDensity(rho, 0.0);
        world.barrier();
        double const t0 = MPI_Wtime();
        FftFreeSpace fft(world, layout, 1.0);
        double const setup = world.allReduce(MPI_Wtime() - t0, core::ReduceOp::Max);
        world.barrier();
        double const t1 = MPI_Wtime();
        fft.solve(rho, phi);
        double const solve = world.allReduce(MPI_Wtime() - t1, core::ReduceOp::Max);
        // Difference to the PETSc potential: both discretisations are second order, so this
        // is the size of their discretisation errors, not a solver tolerance.
        double diff = 0.0;
        double scale = 0.0;
        for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
            for (std::size_t c = 0; c < layout.cellsInBlock(); ++c) {
                auto const pc = layout.padOfInterior(c);
                diff = std::max(diff, std::abs(phi.block(b)[pc] - reference.block(b)[pc]));
                scale = std::max(scale, std::abs(reference.block(b)[pc]));
            }
        diff = world.allReduce(diff, core::ReduceOp::Max);
        scale = world.allReduce(scale, core::ReduceOp::Max);
        double const unknowns = static_cast<double>(layout.globalCellCount());
        if (world.rank() == 0) {
            std::printf("%-9s %6d %10.0f %9s %9.3f %9.3f %5s %10.2e | max|phi_fft - "
                        "phi_gamg| / max|phi| = %.1e\n",
                        "fft", cells, unknowns, "-", setup, solve, "-", solve / unknowns,
                        diff / scale);
            csv << world.size() << "," << cells << "," << unknowns << ",fft,0," << setup << ","
                << solve << ",0," << solve / unknowns << ",,,,,\n";
            std::fflush(stdout);
        }
    }
    return 0;
}
