// Grid self-gravity on the second paper's largest agglomerate (not a test): the
// relative error of g against the direct sum and the time per evaluation, for the bare mesh
// ("pm", grains deposited as volumes) and P3M (points + pair correction within the cut-off)
// at several grid spacings, plus the Barnes–Hut tree and the direct sum on the same grains
// and ranks: the points of the error-versus-time chart. Writes CSV with the columns
// method,param,median_err,p99_err,time_s (+ details).
//
//   mpiexec -n P grid_agglomerate_bench [--grains 38358] [--cells 32,64,128] [--cutoffs 2,4]
//       [--rtol 1e-5] [--order 4] [--repeat 3] [--thetas 0.5,0.7] [--csv out.csv]
//
// Body: gravity::samples::packedAgglomerate(38358, 20 m, 60 m, 3,000 kg/m³, packing 0.3, seed
// 1), as gravity_bench's agg38358. Domain: a cube of half-width 1.2 × the body's radius,
// 4³ blocks. Grains live on the rank whose block holds them. Errors: every grain against the
// distributed direct sum (double-double). Time: the slowest rank's CPU time, median of
// `repeat` evaluations after the first (set-up, AMG hierarchy and calibration excluded: they
// are paid once per forest), each with the body moved by 0.01 h, so the solve starts warm
// from the previous potential as in a run of a slowly moving aggregate (a rigid shift does
// not change the exact field, so the errors stay comparable).
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/P3mGravity.hpp"
#include "gravity/GridGravity.hpp"
#include "gravity/common/ForceError.hpp"
#include "gravity/direct/DirectSum.hpp"
#include "gravity/petsc/PetscSession.hpp"
#include "gravity/samples/SyntheticBodies.hpp"
#include "gravity/tree/BarnesHut.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/BenchOptions.hpp"

using namespace regolith;
namespace gs = regolith::gravity::samples;

namespace {

std::vector<double> numbers(std::string const& s) {
    std::vector<double> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty())
            out.push_back(std::stod(item));
    return out;
}

struct Field {
    std::vector<double> ax, ay, az;
    explicit Field(std::size_t n)
        : ax(n)
        , ay(n)
        , az(n) {}
    gravity::FieldOut out() { return {ax, ay, az}; }
    [[nodiscard]] gravity::AccelView view() const { return {ax, ay, az}; }
};

double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Median over `repeat` runs of the slowest rank's CPU time, s; run(k) for k = 1 .. repeat.
/// CPU, not wall time: on a machine shared with other jobs time-sharing inflates wall time
/// but not the CPU time of one rank (with several ranks, Open MPI's busy waits count too).
double timeIt(core::Comm const& comm, int repeat, std::function<void(int)> const& run) {
    std::vector<double> t;
    for (int k = 1; k <= repeat; ++k) {
        comm.barrier();
        double const t0 = cpuSeconds();
        run(k);
        t.push_back(comm.allReduce(cpuSeconds() - t0, core::ReduceOp::Max));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment env(argc, argv);
    int noArgs = 0;
    char** noArgv = nullptr;
    gravity::PetscSession petsc(noArgs, noArgv);
    core::Comm world(MPI_COMM_WORLD);
    std::size_t grains = 38358;
    std::string cellsList = "32,64,128";
    std::string cutoffs = "2,4";
    std::string thetas = "0.5,0.7";
    double rtol = 1e-5;
    int order = 4;
    int repeat = 3;
    std::string csvPath = "bench/out/grid_agglomerate.csv";
    bench::BenchOptions const cli = bench::parseBenchOptions(
        argc, argv, "grid_agglomerate_bench",
        {"--grains", "--cells", "--cutoffs", "--thetas", "--rtol", "--order", "--repeat", "--csv"},
        world.rank() == 0);
    if (cli.exitCode >= 0)
        return cli.exitCode;
    for (auto const& [key, value] : cli.pairs) {
        if (key == "--grains")
            grains = std::stoul(value);
        else if (key == "--cells")
            cellsList = value;
        else if (key == "--cutoffs")
            cutoffs = value;
        else if (key == "--thetas")
            thetas = value;
        else if (key == "--rtol")
            rtol = std::stod(value);
        else if (key == "--order")
            order = std::stoi(value);
        else if (key == "--repeat")
            repeat = std::stoi(value);
        else if (key == "--csv")
            csvPath = value;
    }
    gs::Body const body =
        gs::packedAgglomerate(grains, 20.0, 60.0, 3000.0, 0.3, core::Vec3::Zero(), 1);
    double radius = 0.0;
    for (std::size_t k = 0; k < body.size(); ++k)
        radius = std::max(radius, std::hypot(body.x[k], body.y[k], body.z[k]) + body.r[k]);
    domain::ForestSpec spec;
    spec.domain =
        core::AABB{core::Vec3::Constant(-1.2 * radius), core::Vec3::Constant(1.2 * radius)};
    spec.rootBlocks = {4, 4, 4};

    FILE* csv = nullptr;
    if (world.rank() == 0) {
        csv = std::fopen(csvPath.c_str(), "w");
        if (csv != nullptr)
            std::fprintf(csv, "method,param,median_err,p99_err,time_s,ranks,grains,cells,h_m,"
                              "cells_across_body,cutoff_cells,iterations,pairs_per_grain,"
                              "halo_grains\n");
        std::printf("agglomerate: %zu grains, radius %.0f m; domain half-width %.0f m, 4^3 "
                    "blocks, %d ranks, rtol %.0e, gradient order %d\n",
                    body.size(), radius, 1.2 * radius, world.size(), rtol, order);
        std::printf("%-7s %-22s %10s %10s %9s %5s %9s %8s\n", "method", "param", "median_err",
                    "p99_err", "time_s", "its", "pairs/gr", "halo");
    }
    auto row = [&](char const* method, std::string const& param, gravity::ErrorStats const& e,
                   double time, int cells, double h, double cutoff, int its, double pairs,
                   double halo) {
        if (world.rank() != 0)
            return;
        std::printf("%-7s %-22s %10.3e %10.3e %9.4f %5d %9.1f %8.0f\n", method, param.c_str(),
                    e.median, e.p99, time, its, pairs, halo);
        std::fflush(stdout);
        if (csv != nullptr) {
            std::fprintf(csv, "%s,%s,%.4e,%.4e,%.5f,%d,%zu,%d,%.2f,%.1f,%g,%d,%.1f,%.0f\n", method,
                         param.c_str(), e.median, e.p99, time, world.size(), body.size(), cells, h,
                         h > 0.0 ? 2.0 * radius / h : 0.0, cutoff, its, pairs, halo);
            std::fflush(csv);
        }
    };

    // Grains of this rank's blocks (the forest's assignment is the same for every grid).
    domain::BlockForest const layoutForest(world, spec);
    gs::Body local;
    for (std::size_t k = 0; k < body.size(); ++k)
        if (layoutForest.localBlockContaining({body.x[k], body.y[k], body.z[k]}) != nullptr)
            local.push(body, k);
    std::size_t const n = local.size();
    Field reference(n);
    gravity::direct::DirectSum direct(world, {});
    double const directTime =
        timeIt(world, 1, [&](int) { direct.evaluate(local.view(), reference.out()); });
    auto const stats = [&](Field const& f) {
        return gravity::errorStats(world, gravity::relativeErrors(f.view(), reference.view()));
    };
    row("direct", "exact", {}, directTime, 0, 0.0, 0.0, 0, 0.0, 0.0);

    Field f(n);
    for (double theta : numbers(thetas)) {
        gravity::tree::TreeOptions o;
        o.theta = theta;
        gravity::tree::BarnesHut tree(world, o);
        double const t = timeIt(world, repeat, [&](int) { tree.evaluate(local.view(), f.out()); });
        std::ostringstream p;
        p << "theta=" << theta;
        row("tree", p.str(), stats(f), t, 0, 0.0, 0.0, 0, 0.0, 0.0);
    }

    std::string const petscOptions = "-ksp_rtol " + std::to_string(rtol);
    for (double cellsD : numbers(cellsList)) {
        int const cells = static_cast<int>(cellsD);
        spec.cellsPerBlock = {cells / 4, cells / 4, cells / 4};
        domain::BlockForest const forest(world, spec);
        double const h = 2.4 * radius / cells;
        // Positions moved by k * 0.01 h along x for evaluation k (see the header).
        std::vector<core::Vec3> position(n);
        auto const place = [&](int k) {
            for (std::size_t i = 0; i < n; ++i)
                position[i] = core::Vec3(local.x[i] + 0.01 * h * k, local.y[i], local.z[i]);
        };
        std::vector<double> x(n), y(n), z(n);
        auto const placeSoA = [&](int k) {
            place(k);
            for (std::size_t i = 0; i < n; ++i) {
                x[i] = position[i].x();
                y[i] = position[i].y();
                z[i] = position[i].z();
            }
        };
        std::ostringstream grid;
        grid << cells << "^3 h=" << std::lround(h) << "m";
        {
            gravity::GridGravityOptions o;
            o.gradientOrder = order;
            o.poisson.G = gravity::kNewtonG;
            o.poisson.petscOptions = petscOptions;
            gravity::GridGravity pm(world, forest, spec.cellsPerBlock, o);
            std::vector<core::Vec3> g(n);
            gravity::SolveStats last;
            auto const evaluate = [&](int k) {
                place(k);
                gravity::Grains const gr{position, local.r, local.m};
                last = pm.update(gr);
                pm.accelerations(gr, g);
            };
            evaluate(0); // set-up
            double const t = timeIt(world, repeat, evaluate);
            for (std::size_t i = 0; i < n; ++i) {
                f.ax[i] = g[i].x();
                f.ay[i] = g[i].y();
                f.az[i] = g[i].z();
            }
            row("pm", grid.str(), stats(f), t, cells, h, 0.0, last.iterations, 0.0, 0.0);
        }
        for (double cutoff : numbers(cutoffs)) {
            coupling::SelfGravityConfig c;
            c.method = "p3m";
            c.cellsPerBlock = spec.cellsPerBlock;
            c.gradientOrder = order;
            c.petscOptions = petscOptions;
            c.p3mCutoffCells = cutoff;
            coupling::P3mGravity p3m(world, forest, c);
            auto const evaluate = [&](int k) {
                placeSoA(k);
                p3m.evaluate({x, y, z, local.m}, f.out());
            };
            evaluate(0);
            double const t = timeIt(world, repeat, evaluate);
            double const pairs =
                world.allReduce(static_cast<double>(p3m.pairsLastEvaluate()), core::ReduceOp::Sum) /
                static_cast<double>(body.size());
            double const halo =
                world.allReduce(static_cast<double>(p3m.halo().mass().size()), core::ReduceOp::Sum);
            std::ostringstream p;
            p << grid.str() << " rc=" << cutoff << "h";
            row("p3m", p.str(), stats(f), t, cells, h, cutoff, p3m.lastSolve().iterations, pairs,
                halo);
        }
    }
    if (csv != nullptr)
        std::fclose(csv);
    return 0;
}
