// Self-gravity benchmark (not a test): time per force evaluation and relative force
// error against the direct sum for the second paper's agglomerates (3,866 / 11,100 / 38,358
// grains) and Plummer spheres (10⁵, 10⁶, optionally 2.1 × 10⁶), for every method and θ.
//
//   mpiexec -n P gravity_bench [--instances agg3866,agg11100,agg38358,plummer1e5,plummer1e6]
//       [--methods direct,tree,mutual,occupied-cells,tree-nodes] [--thetas 0.3,0.5,0.7,0.9]
//       [--samples 2000] [--repeat 3] [--csv out.csv] [--opening bmax-offset|bmax|edge-offset]
//       [--leaf 8] [--group 64]
//       [--node-spacings 2.5]                      (occupied-cells, tree-nodes)
//       [--spacings 4,2,1,0.5] [--pm-gradient 4] [--pm-rtol 1e-6]          (method pm)
//       [--thresholds 0.01,0.1,1,6] [--step-displacement 0.001] [--stale-theta 0.5]
//                                                                      (method stale-tree)
//
// Added for the charts (not in the default --methods): `pm`, the particle-mesh method
// (gravity/GridGravity, TSC, PETSc CG+GAMG from a cold start, set-up not counted, best of two)
// at cell spacings given as multiples of the largest grain diameter; `stale-tree`, the update
// threshold (StaleFieldStudy.hpp: the tree field at --stale-theta kept until the fastest grain
// moved the threshold, given in multiples of the smallest grain radius, one rank only; time per
// step amortised for a fastest grain moving --step-displacement smallest radii per step).
// The grid baselines at node spacings given as multiples of the largest diameter. θ > 1 is
// allowed (gravity.allow_large_theta). CSV columns `spacing` (h or node spacing / the largest
// diameter) and `threshold` (/ the smallest radius) say which parameter a row varies.
//
// Errors: on a sample of about `samples` grains (every k-th grain of each rank), against the
// direct sum for those grains over all grains (double-double, DirectKernel.hpp). Time: the
// slowest rank's wall time, median of `repeat` evaluations. The full direct sum is timed
// only up to 40,000 grains, the grid methods only on the agglomerates (their grid spacing is
// the paper's 2.5 × the largest diameter), the mutual tree only on one rank (serial kernel).
#include "core/mpi/Comm.hpp"
#include "gravity/baselines/GridMethods.hpp"
#include "gravity/common/ForceError.hpp"
#include "gravity/direct/DirectSum.hpp"
#include "gravity/petsc/PetscSession.hpp"
#include "gravity/samples/SyntheticBodies.hpp"
#include "gravity/tree/BarnesHut.hpp"
#include "gravity/tree/MutualTree.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/BenchOptions.hpp"
#include "bench/gravity/MeshEvaluation.hpp"
#include "bench/gravity/StaleFieldStudy.hpp"

using namespace regolith;
namespace gs = regolith::gravity::samples;

namespace {

struct Instance {
    std::string name;
    gs::Body body;
    bool agglomerate = false;
    double largestRadius = 0.0;
};

std::vector<std::string> split(std::string const& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty())
            out.push_back(item);
    return out;
}

Instance makeInstance(std::string const& name) {
    Instance inst;
    inst.name = name;
    auto const agg = [&](std::size_t n, double r0, double r1) {
        inst.body = gs::packedAgglomerate(n, r0, r1, 3000.0, 0.3, core::Vec3::Zero(), 1);
        inst.agglomerate = true;
        inst.largestRadius = r1;
    };
    if (name == "agg3866")
        agg(3866, 50.0, 100.0);
    else if (name == "agg11100")
        agg(11100, 35.0, 70.0);
    else if (name == "agg38358")
        agg(38358, 20.0, 60.0);
    else if (name == "plummer1e5")
        inst.body = gs::plummerSphere(100000, 1e12, 1000.0, 1);
    else if (name == "plummer1e6")
        inst.body = gs::plummerSphere(1000000, 1e12, 1000.0, 1);
    else if (name == "plummer2.1e6")
        inst.body = gs::plummerSphere(2100000, 1e12, 1000.0, 1);
    else
        throw std::runtime_error("unknown instance " + name);
    return inst;
}

struct Field {
    std::vector<double> ax, ay, az, phi;
    explicit Field(std::size_t n)
        : ax(n)
        , ay(n)
        , az(n)
        , phi(n) {}
    gravity::FieldOut out() { return {ax, ay, az, phi}; }
};

double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// CPU time of the last timeIt() (median, slowest rank), s: on a loaded machine the fairer
/// figure for "one core".
double g_cpu = 0.0;

/// Median over `repeat` runs of the slowest rank's wall time for `run`, in s.
double timeIt(core::Comm const& comm, int repeat, std::function<void()> const& run) {
    std::vector<double> t;
    std::vector<double> c;
    for (int k = 0; k < repeat; ++k) {
        comm.barrier();
        double const t0 = MPI_Wtime();
        double const c0 = cpuSeconds();
        run();
        c.push_back(comm.allReduce(cpuSeconds() - c0, core::ReduceOp::Max));
        t.push_back(comm.allReduce(MPI_Wtime() - t0, core::ReduceOp::Max));
    }
    std::sort(t.begin(), t.end());
    std::sort(c.begin(), c.end());
    g_cpu = c[c.size() / 2];
    return t[t.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    core::MpiEnvironment env(argc, argv);
    core::Comm world(MPI_COMM_WORLD);
    std::string instances = "agg3866,agg11100,agg38358,plummer1e5,plummer1e6";
    std::string methods = "direct,tree,mutual,occupied-cells,tree-nodes";
    std::string thetas = "0.3,0.5,0.7,0.9";
    std::size_t samples = 2000;
    int repeat = 3;
    std::string csv;
    int leafSize = gravity::tree::TreeOptions{}.leafSize;
    auto criterion = gravity::tree::TreeOptions{}.criterion;
    int groupSize = gravity::tree::TreeOptions{}.groupSize;
    std::string spacings = "4,2,1,0.5";
    std::string nodeSpacings = "2.5"; // the paper's: 2.5 x the largest diameter
    bench::MeshSetup meshSetup;
    std::string thresholds = "0.01,0.1,1,6";
    double stepDisplacement = 0.001;
    double staleTheta = 0.5;
    bench::BenchOptions const cli = bench::parseBenchOptions(
        argc, argv, "gravity_bench",
        {"--instances", "--methods", "--thetas", "--samples", "--repeat", "--csv", "--opening",
         "--leaf", "--group", "--spacings", "--node-spacings", "--pm-gradient", "--pm-rtol",
         "--thresholds", "--step-displacement", "--stale-theta"},
        world.rank() == 0);
    if (cli.exitCode >= 0)
        return cli.exitCode;
    for (auto const& [key, value] : cli.pairs) {
        if (key == "--instances")
            instances = value;
        else if (key == "--methods")
            methods = value;
        else if (key == "--thetas")
            thetas = value;
        else if (key == "--samples")
            samples = std::stoul(value);
        else if (key == "--repeat")
            repeat = std::stoi(value);
        else if (key == "--csv")
            csv = value;
        else if (key == "--opening")
            criterion = gravity::tree::parseOpeningCriterion(value);
        else if (key == "--leaf")
            leafSize = std::stoi(value);
        else if (key == "--group")
            groupSize = std::stoi(value);
        else if (key == "--spacings")
            spacings = value;
        else if (key == "--node-spacings")
            nodeSpacings = value;
        else if (key == "--pm-gradient")
            meshSetup.gradientOrder = std::stoi(value);
        else if (key == "--pm-rtol")
            meshSetup.rtol = std::stod(value);
        else if (key == "--thresholds")
            thresholds = value;
        else if (key == "--step-displacement")
            stepDisplacement = std::stod(value);
        else if (key == "--stale-theta")
            staleTheta = std::stod(value);
    }
    auto const want = split(methods);
    auto const has = [&](char const* m) {
        return std::find(want.begin(), want.end(), m) != want.end();
    };
    std::optional<gravity::PetscSession> petsc; // opened for the first pm point
    FILE* out = nullptr;
    if (world.rank() == 0) {
        std::printf("%-13s %9s %5s %-15s %5s %11s %11s %9s %10s %10s\n", "instance", "N", "ranks",
                    "method", "theta", "wall_ms", "cpu_ms", "ns/grain", "err_median", "err_p99");
        if (!csv.empty()) {
            out = std::fopen(csv.c_str(), "w");
            if (out != nullptr)
                std::fprintf(out, "instance,N,ranks,method,theta,wall_ms,cpu_ms,cpu_ns_per_grain,"
                                  "err_median,err_p99,spacing,threshold\n");
        }
    }
    for (std::string const& name : split(instances)) {
        Instance const inst = makeInstance(name);
        std::size_t const n = inst.body.size();
        gs::Body const local = gs::slabOf(inst.body, world.rank(), world.size());
        // The error sample: every k-th local grain, with its exact field.
        std::size_t const stride = std::max<std::size_t>(1, n / samples);
        gs::Body sample;
        std::vector<std::size_t> sampleIndex;
        for (std::size_t i = 0; i < local.size(); i += stride) {
            sample.push(local, i);
            sampleIndex.push_back(i);
        }
        Field ref(sample.size());
        gravity::direct::directSumSerial(sample.view(), inst.body.view(), ref.out(), {});
        // `spacing`, `threshold`: the grid / threshold parameter of the row (0 if none).
        auto const reportStats = [&](char const* method, double theta, double seconds,
                                     gravity::ErrorStats const& e, double spacing = 0.0,
                                     double threshold = 0.0) {
            if (world.rank() != 0)
                return;
            double const ms = 1e3 * seconds;
            double const cpuMs = 1e3 * g_cpu;
            double const ns = 1e9 * g_cpu / static_cast<double>(n);
            std::printf("%-13s %9zu %5d %-15s %5.2f %11.2f %11.2f %9.1f %10.3e %10.3e\n",
                        name.c_str(), n, world.size(), method, theta, ms, cpuMs, ns, e.median,
                        e.p99);
            std::fflush(stdout);
            if (out != nullptr)
                std::fprintf(out, "%s,%zu,%d,%s,%.2f,%.4f,%.4f,%.3f,%.4e,%.4e,%g,%g\n",
                             name.c_str(), n, world.size(), method, theta, ms, cpuMs, ns, e.median,
                             e.p99, spacing, threshold);
        };
        auto const report = [&](char const* method, double theta, double seconds, Field const& f,
                                double spacing = 0.0) {
            std::vector<double> ax, ay, az;
            for (std::size_t k : sampleIndex) {
                ax.push_back(f.ax[k]);
                ay.push_back(f.ay[k]);
                az.push_back(f.az[k]);
            }
            auto const e = gravity::errorStats(
                world, gravity::relativeErrors({ax, ay, az}, {ref.ax, ref.ay, ref.az}));
            reportStats(method, theta, seconds, e, spacing);
        };
        Field f(local.size());
        if (has("direct") && n <= 40000) {
            gravity::direct::DirectSum direct(world, {});
            double const t = timeIt(world, 1, [&] { direct.evaluate(local.view(), f.out()); });
            report("direct", 0.0, t, f);
        }
        for (std::string const& ts : split(thetas)) {
            double const theta = std::stod(ts);
            gravity::tree::TreeOptions o;
            o.theta = theta;
            o.leafSize = leafSize;
            o.groupSize = groupSize;
            o.criterion = criterion;
            o.allowLargeTheta = theta > 1.0; // the charts show where the criterion fails
            if (has("tree")) {
                gravity::tree::BarnesHut tree(world, o);
                double const t =
                    timeIt(world, repeat, [&] { tree.evaluate(local.view(), f.out()); });
                report("tree", theta, t, f);
                if (world.rank() == 0)
                    std::printf("    tree interactions per grain: %.0f cells, %.0f grains\n",
                                static_cast<double>(tree.stats().cellInteractions) /
                                    static_cast<double>(local.size()),
                                static_cast<double>(tree.stats().grainInteractions) /
                                    static_cast<double>(local.size()));
            }
            if (has("mutual") && world.size() == 1) {
                gravity::tree::MutualTree mutual(o);
                double const t =
                    timeIt(world, repeat, [&] { mutual.evaluate(local.view(), f.out()); });
                report("mutual", theta, t, f);
            }
            for (std::string const& ns : split(nodeSpacings)) {
                if (!has("tree-nodes") || !inst.agglomerate)
                    break;
                gravity::baselines::GridMethodOptions g;
                g.grid.spacing = std::stod(ns) * 2.0 * inst.largestRadius;
                g.theta = theta;
                g.allowLargeTheta = theta > 1.0;
                g.neighbourhood = g.grid.spacing;
                gravity::baselines::TreeAtNodes method(g);
                double const t = timeIt(world, std::min(repeat, 2),
                                        [&] { method.evaluate(world, local.view(), f.out()); });
                report("tree-nodes", theta, t, f, std::stod(ns));
            }
        }
        for (std::string const& ns : split(nodeSpacings)) {
            if (!has("occupied-cells") || !inst.agglomerate)
                break;
            gravity::baselines::GridMethodOptions g;
            g.grid.spacing = std::stod(ns) * 2.0 * inst.largestRadius;
            gravity::baselines::OccupiedCells method(g);
            double const t =
                timeIt(world, 1, [&] { method.evaluate(world, local.view(), f.out()); });
            report("occupied-cells", 0.0, t, f, std::stod(ns));
        }
        if (has("pm") && inst.agglomerate) {
            if (!petsc) {
                int petscArgc = 0;
                char** petscArgv = nullptr;
                petsc.emplace(petscArgc, petscArgv);
            }
            for (std::string const& s : split(spacings)) {
                bench::MeshSetup setup = meshSetup;
                setup.spacing = std::stod(s) * 2.0 * inst.largestRadius;
                bench::MeshEvaluation mesh(world, inst.body, setup);
                double wall = 1e300;
                double cpu = 1e300;
                int iterations = 0;
                for (int k = 0; k < std::min(repeat, 2); ++k) {
                    auto const t = mesh.evaluate(local.view(), f.out());
                    wall = std::min(wall, t.wall);
                    cpu = std::min(cpu, t.cpu);
                    iterations = t.iterations;
                }
                g_cpu = cpu;
                report("pm", 0.0, wall, f, mesh.spacing() / (2.0 * inst.largestRadius));
                if (world.rank() == 0)
                    std::printf("    pm: %d^3 cells, h = %.1f m, %d iterations\n",
                                mesh.cellsPerAxis(), mesh.spacing(), iterations);
            }
        }
        if (has("stale-tree") && world.size() == 1 && inst.agglomerate) {
            gravity::tree::TreeOptions o;
            o.theta = staleTheta;
            o.leafSize = leafSize;
            o.groupSize = groupSize;
            o.criterion = criterion;
            gravity::tree::BarnesHut tree(world, o);
            double const evalWall =
                timeIt(world, repeat, [&] { tree.evaluate(local.view(), f.out()); });
            double const evalCpu = g_cpu;
            double rMin = 1e300;
            for (double r : local.r)
                rMin = std::min(rMin, r);
            bench::StaleFieldStudy study(local, sampleIndex);
            for (std::string const& s : split(thresholds)) {
                double const multiple = std::stod(s);
                auto const p = study.point(world, multiple * rMin, stepDisplacement * rMin,
                                           {f.ax, f.ay, f.az}, evalWall, evalCpu);
                g_cpu = p.cpuSeconds;
                reportStats("stale-tree", staleTheta, p.wallSeconds, p.error, 0.0, multiple);
                if (world.rank() == 0)
                    std::printf("    stale: threshold %.3g m, an update every %.0f steps, "
                                "check %.3f ms\n",
                                p.threshold, p.stepsPerUpdate, 1e3 * p.dueSeconds);
            }
        }
    }
    if (out != nullptr)
        std::fclose(out);
    return 0;
}
