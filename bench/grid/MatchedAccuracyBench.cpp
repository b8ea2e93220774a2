// PETSc against the FFT reference at equal accuracy (not a test). For the free-space
// potential of two smooth balls (the density of grid_bench, whose potential is analytic), the
// error of φ against the analytic potential, and the solve time, of
//  - the FFT reference (Hockney–Eastwood, rank 0), and
//  - each PETSc solver with its set-up reused, at a ladder of relative tolerances: the cold
//    solve and the warm solve after the mass moved by 0.01 h (a slowly moving aggregate).
// "Matched tolerance": the largest tolerance whose cold φ error is within 5 % of the converged
// PETSc error (rtol 1e-10: the discretisation error alone) — tighter buys nothing. At that
// tolerance a warm start after a small move often needs 0-1 iterations: the previous
// potential is already that accurate. Times: CPU seconds of the whole call (median of 3 for
// the FFT). Prints the table and the ratios to the FFT; writes CSV.
//
//   mpiexec -n P grid_matched_bench [--min-cells 32] [--max-cells 128] [--csv out.csv]
//       [--solvers gamg,hypre,gamg-tuned] [--rtols 1e-2,1e-3,...,1e-10 (loosest first; the
//       last is taken as converged)]
#include "gravity/fft/FftFreeSpace.hpp"
#include "gravity/field/CellLayout.hpp"
#include "gravity/petsc/PetscSession.hpp"
#include "gravity/poisson/PoissonSolver.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/BenchOptions.hpp"

using namespace regolith;
using namespace regolith::gravity;

namespace {

/// One ball of density (1 - r²/R²)² inside R: its potential for G = 1 (Poisson's equation
/// integrated radially: M(r) = 4π (r³/3 - 2r⁵/(5R²) + r⁷/(7R⁴)); inside, φ = -M(r)/r -
/// 4π R²/6 (1 - r²/R²)³; outside, -M(R)/r).
double ballPotential(double r, double R) {
    auto const mass = [R](double s) {
        return 4.0 * std::numbers::pi *
               (s * s * s / 3.0 - 2.0 * std::pow(s, 5) / (5.0 * R * R) +
                std::pow(s, 7) / (7.0 * std::pow(R, 4)));
    };
    if (r >= R)
        return -mass(R) / r;
    double const u = 1.0 - r * r / (R * R);
    double const inner = r > 0.0 ? mass(r) / r : 0.0;
    return -inner - 4.0 * std::numbers::pi * R * R / 6.0 * u * u * u;
}

struct Ball {
    core::Vec3 centre;
    double R;
};
std::vector<Ball> balls(double shift) {
    return {{{shift, 0.0, 0.0}, 0.5}, {{0.6 + shift, 0.3, 0.0}, 0.2}};
}

/// Density at cell centres (shifted by `shift` along x) and, if `exact`, the analytic φ.
void fill(CellLayout const& layout, double shift, CellField& rho, CellField* exact) {
    auto const& n = layout.cellsPerBlock();
    rho.fill(0.0);
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    auto const& o = layout.origin(b);
                    core::Vec3 const x = layout.centre({o[0] + i, o[1] + j, o[2] + k});
                    double density = 0.0, phi = 0.0;
                    for (Ball const& ball : balls(shift)) {
                        double const r = (x - ball.centre).norm();
                        double const u = 1.0 - r * r / (ball.R * ball.R);
                        density += r < ball.R ? u * u : 0.0;
                        phi += ballPotential(r, ball.R);
                    }
                    rho.at(b, i, j, k) = density;
                    if (exact != nullptr)
                        exact->at(b, i, j, k) = phi;
                }
}

/// max |φ - φ_exact| / max |φ_exact| over all interior cells. COLLECTIVE.
double error(core::Comm const& comm, CellField const& phi, CellField const& exact) {
    auto const& layout = phi.layout();
    double diff = 0.0, scale = 0.0;
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (std::size_t c = 0; c < layout.cellsInBlock(); ++c) {
            auto const pc = layout.padOfInterior(c);
            diff = std::max(diff, std::abs(phi.block(b)[pc] - exact.block(b)[pc]));
            scale = std::max(scale, std::abs(exact.block(b)[pc]));
        }
    return comm.allReduce(diff, core::ReduceOp::Max) / comm.allReduce(scale, core::ReduceOp::Max);
}

double maxOver(core::Comm const& comm, double v) {
    return comm.allReduce(v, core::ReduceOp::Max);
}

/// Process CPU time [s]: on a machine shared with other jobs a fairer figure than wall time
/// for one rank (time-sharing does not inflate it; Open MPI's busy waits would, with several).
double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// A solve and its CPU seconds (slowest rank), boundary values and copies included.
SolveStats timedSolve(core::Comm const& comm, PoissonSolver& solver, CellField const& rho,
                      CellField& phi, double& seconds) {
    double const c0 = cpuSeconds();
    SolveStats const s = solver.solve(rho, phi);
    seconds = maxOver(comm, cpuSeconds() - c0);
    return s;
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment mpi(argc, argv);
    int noArgs = 0;
    char** noArgv = nullptr;
    PetscSession petsc(noArgs, noArgv);
    core::Comm world;
    int minCells = 32, maxCells = 128;
    std::string csvPath = "bench/out/grid_matched.csv";
    std::string solverList = "gamg,hypre,gamg-tuned";
    std::string rtolList = "1e-2,1e-3,1e-4,1e-5,1e-6,1e-8,1e-10"; // ascending tightness
    bench::BenchOptions const cli = bench::parseBenchOptions(
        argc, argv, "grid_matched_bench",
        {"--min-cells", "--max-cells", "--csv", "--solvers", "--rtols"}, world.rank() == 0);
    if (cli.exitCode >= 0)
        return cli.exitCode;
    for (auto const& [key, value] : cli.pairs) {
        if (key == "--min-cells")
            minCells = std::atoi(value.c_str());
        else if (key == "--max-cells")
            maxCells = std::atoi(value.c_str());
        else if (key == "--csv")
            csvPath = value;
        else if (key == "--solvers")
            solverList = value;
        else if (key == "--rtols")
            rtolList = value;
    }
    std::vector<std::pair<std::string, std::string>> solvers;
    auto want = [&](char const* s) { return solverList.find(s) != std::string::npos; };
    if (want("gamg"))
        solvers.emplace_back("cg+gamg", "-ksp_type cg -pc_type gamg");
    if (want("hypre"))
        solvers.emplace_back("cg+hypre", "-ksp_type cg -pc_type hypre -pc_hypre_type boomeramg");
    if (want("gamg-tuned")) // one smoothing sweep, no graph squaring: cheaper cycles
        solvers.emplace_back("cg+gamg-tuned", "-ksp_type cg -pc_type gamg -pc_gamg_agg_nsmooths 1 "
                                              "-pc_gamg_square_graph 0 -mg_levels_ksp_max_it 1 "
                                              "-pc_gamg_threshold 0.02");
    std::vector<double> rtols;
    {
        std::stringstream in(rtolList);
        std::string item;
        while (std::getline(in, item, ','))
            rtols.push_back(std::stod(item));
    }
    std::ofstream csv;
    if (world.rank() == 0) {
        csv.open(csvPath);
        csv << "ranks,cells,solver,rtol,cold_phi_error,cold_iterations,cold_s,warm_iterations,"
               "warm_s,warm026_iterations,warm026_s,warm_phi_error\n";
        std::printf("%d ranks; φ error = max|φ - φ_exact| / max|φ_exact|; warm = after a 0.01 h "
                    "move\n",
                    world.size());
        std::printf("%-14s %5s %8s %10s %9s %9s %9s %9s %9s %9s %10s\n", "solver", "cells", "rtol",
                    "cold_err", "cold_its", "cold_s", "warm_its", "warm_s", "w.25_its", "w.25_s",
                    "warm_err");
    }
    for (int cells = minCells; cells <= maxCells; cells *= 2) {
        domain::ForestSpec spec;
        spec.domain = core::AABB{core::Vec3::Constant(-2.0), core::Vec3::Constant(2.0)};
        int const bpa = cells >= 64 ? 4 : 2;
        spec.rootBlocks = {bpa, bpa, bpa};
        spec.cellsPerBlock = {cells / bpa, cells / bpa, cells / bpa};
        domain::BlockForest forest(world, spec);
        CellLayout layout(world, forest, spec.cellsPerBlock, 1);
        double const h = layout.spacing()[0];
        CellField rho(layout), phi(layout), exact(layout), exactMoved(layout);
        fill(layout, 0.01 * h, rho, &exactMoved);
        fill(layout, 0.0, rho, &exact);
        // FFT: median of 3 solves.
        FftFreeSpace fft(world, layout, 1.0);
        std::vector<double> t;
        for (int r = 0; r < 3; ++r) {
            world.barrier();
            double const c0 = cpuSeconds();
            fft.solve(rho, phi);
            t.push_back(maxOver(world, cpuSeconds() - c0));
        }
        std::sort(t.begin(), t.end());
        double const fftTime = t[1];
        double const fftError = error(world, phi, exact);
        if (world.rank() == 0) {
            std::printf("%-14s %5d %8s %10.3e %9s %9s %9s %9.4f\n", "fft", cells, "-", fftError,
                        "-", "-", "-", fftTime);
            csv << world.size() << "," << cells << ",fft,0," << fftError << ",0," << fftTime
                << ",0," << fftTime << ",0," << fftTime << "," << fftError << "\n";
        }
        for (auto const& [name, options] : solvers) {
            PoissonOptions po;
            po.G = 1.0;
            po.petscOptions = options;
            PoissonSolver solver(world, layout, po);
            fill(layout, 0.0, rho, nullptr);
            solver.solve(rho, phi); // set-up (AMG hierarchy), reused below
            struct Point {
                double rtol, coldErr, coldS, warmS;
                int coldIts, warmIts;
            };
            std::vector<Point> points;
            for (double rtol : rtols) {
                solver.setRelativeTolerance(rtol);
                // Cold (set-up reused, zero initial guess) at shift 0: its error decides
                // whether this tolerance is already at the discretisation's accuracy.
                fill(layout, 0.0, rho, nullptr);
                solver.resetInitialGuess();
                double coldS = 0.0;
                SolveStats const cold = timedSolve(world, solver, rho, phi, coldS);
                double const coldErr = error(world, phi, exact);
                // Warm: the mass moved by 0.01 h, then by 0.25 h more, each from the last
                // solution (consecutive steps of a slowly / a faster moving aggregate).
                fill(layout, 0.01 * h, rho, nullptr);
                double warmS = 0.0;
                SolveStats const warm = timedSolve(world, solver, rho, phi, warmS);
                double const warmErr = error(world, phi, exactMoved);
                fill(layout, 0.26 * h, rho, nullptr);
                double warmBigS = 0.0;
                SolveStats const warmBig = timedSolve(world, solver, rho, phi, warmBigS);
                points.push_back({rtol, coldErr, coldS, warmS, cold.iterations, warm.iterations});
                if (world.rank() == 0) {
                    std::printf("%-14s %5d %8.0e %10.3e %9d %9.4f %9d %9.4f %9d %9.4f %10.3e\n",
                                name.c_str(), cells, rtol, coldErr, cold.iterations, coldS,
                                warm.iterations, warmS, warmBig.iterations, warmBigS, warmErr);
                    csv << world.size() << "," << cells << "," << name << "," << rtol << ","
                        << coldErr << "," << cold.iterations << "," << coldS << ","
                        << warm.iterations << "," << warmS << "," << warmBig.iterations << ","
                        << warmBigS << "," << warmErr << "\n";
                }
            }
            if (points.empty())
                continue;
            double const best = points.back().coldErr;
            auto const matched = std::find_if(points.begin(), points.end(), [&](Point const& p) {
                return p.coldErr <= 1.05 * best;
            });
            if (world.rank() == 0)
                std::printf("  -> %s at %d^3: matched rtol %.0e (cold φ error %.3e; converged "
                            "%.3e; FFT %.3e): cold %d its %.4f s = %.2f x the FFT; warm (0.01 h) "
                            "%d its %.4f s = %.2f x\n",
                            name.c_str(), cells, matched->rtol, matched->coldErr, best, fftError,
                            matched->coldIts, matched->coldS, matched->coldS / fftTime,
                            matched->warmIts, matched->warmS, matched->warmS / fftTime);
        }
        if (world.rank() == 0)
            std::fflush(stdout);
    }
    return 0;
}
