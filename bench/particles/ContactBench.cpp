// Contact detection + contact evaluation cost per particle-step for the sparse gas and for
// the same lattice around one radius-30 sphere (the bidisperse scene of Eibl & Ruede 2018,
// Table 1, scaled to one block), and bytes per particle. Prints the per-particle ratio of
// the two scenes; the target is that the large sphere costs at most 1.5x per particle.
//
//   particles_bench [--benchmark_out=contact.json --benchmark_out_format=json]
#include "particles/detection/ContactDetector.hpp"
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/SpringDashpot.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <sys/resource.h>

#include "bench/particles/OneMaterial.hpp"

namespace {

using namespace regolith::particles;
using regolith::core::Vec3;

constexpr double kRadius = 0.4;
constexpr double kDensity = 1.0;

double massOf(double r) {
    return kDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

/// An n^3 simple-cubic lattice of spacing 1 (sites at i + 0.5), random velocities in
/// [-0.1, 0.1]^3, optionally around a sphere of radius `bigRadius` in the middle (lattice
/// sites whose grain would overlap it are skipped).
ParticleStorage latticeScene(int n, double bigRadius) {
    ParticleStorage ps;
    ps.reserve(static_cast<std::size_t>(n) * n * n + 1);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    UidGenerator uids(0);
    Vec3 const centre = Vec3::Constant(0.5 * n);
    if (bigRadius > 0.0) {
        ParticleInit big;
        big.uid = uids.next();
        big.position = centre;
        big.radius = bigRadius;
        big.mass = massOf(bigRadius);
        ps.add(big);
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                Vec3 const x = Vec3(i, j, k) + Vec3::Constant(0.5);
                if (bigRadius > 0.0 && (x - centre).norm() < bigRadius + kRadius)
                    continue;
                ParticleInit p;
                p.uid = uids.next();
                p.position = x;
                p.velocity = Vec3(u(rng), u(rng), u(rng));
                p.radius = kRadius;
                p.mass = massOf(kRadius);
                ps.add(p);
            }
    return ps;
}

SpringDashpot model() {
    return regolith::bench::oneMaterialSpringDashpot(1e3, 0.9, 0.5);
}

std::map<std::string, double> g_nsPerParticleStep; // filled by the scene benchmarks

/// One block's steps; manual time = detection + contact evaluation only.
void runScene(benchmark::State& state, std::string const& name, int n, double bigRadius) {
    ParticleStorage ps = latticeScene(n, bigRadius);
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    // Put neighbours next to each other in memory once, as a run would every few hundred
    // steps (the generator's order is x-slowest, the cells' x-fastest).
    detector.detect(ps, walls, everywhere(), contacts);
    ps.permute(detector.spatialOrder());
    SpringDashpot const contactModel = model();
    double const dt =
        SpringDashpot::contactTime(contactModel.materials()(0, 0), massOf(kRadius) / 2) / 20.0;
    VelocityVerlet const integrator;
    std::uint32_t stamp = 0;
    double seconds = 0.0;
    std::size_t steps = 0, contactsTotal = 0;
    for (auto _ : state) {
        integrator.preForce(ps, dt, Vec3::Zero());
        ps.resetForces();
        auto const t0 = std::chrono::steady_clock::now();
        detector.detect(ps, walls, everywhere(), contacts);
        evaluateContacts(ps, walls, contacts, contactModel, dt, ++stamp);
        pruneHistory(ps, stamp);
        auto const t1 = std::chrono::steady_clock::now();
        integrator.postForce(ps, dt, Vec3::Zero());
        double const s = std::chrono::duration<double>(t1 - t0).count();
        state.SetIterationTime(s);
        seconds += s;
        ++steps;
        contactsTotal += contacts.size();
    }
    double const ns = 1e9 * seconds / (static_cast<double>(steps) * static_cast<double>(ps.size()));
    g_nsPerParticleStep[name] = ns;
    state.counters["particles"] = static_cast<double>(ps.size());
    state.counters["ns_per_particle_step"] = ns;
    state.counters["contacts_per_step"] =
        static_cast<double>(contactsTotal) / static_cast<double>(steps);
    state.counters["cells"] = static_cast<double>(detector.stats().cells);
    state.counters["cell_edge"] = detector.stats().cellEdge;
    state.counters["large"] = static_cast<double>(detector.stats().largeSpheres);
    state.counters["storage_bytes_per_particle"] =
        static_cast<double>(ps.bytes()) / static_cast<double>(ps.size());
    state.counters["detector_bytes_per_particle"] =
        static_cast<double>(detector.bytes()) / static_cast<double>(ps.size());
}

void sparseGas(benchmark::State& state) {
    runScene(state, "sparse", 20, 0.0);
}
void largeSphere(benchmark::State& state) {
    runScene(state, "large", 80, 30.0);
}
BENCHMARK(sparseGas)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(largeSphere)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);

long currentRssKb() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

/// Builds 1,000,000 grains (100^3 lattice), runs one detection + evaluation, and prints the
/// storage bytes per particle and the peak RSS of the process (getrusage). Run first, so the
/// peak is this scene's.
void memoryFigure() {
    long const before = currentRssKb();
    ParticleStorage ps = latticeScene(100, 0.0);
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    SpringDashpot const contactModel = model();
    detector.detect(ps, walls, everywhere(), contacts);
    evaluateContacts(ps, walls, contacts, contactModel, 1e-3, 1);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    double const n = static_cast<double>(ps.size());
    std::printf("memory: %zu grains: storage %.1f bytes/particle, detector %.1f bytes/particle; "
                "peak RSS %.1f MB (%.1f MB before building; %.1f bytes/particle above that)\n",
                ps.size(), static_cast<double>(ps.bytes()) / n,
                static_cast<double>(detector.bytes()) / n,
                static_cast<double>(usage.ru_maxrss) / 1024.0, static_cast<double>(before) / 1024.0,
                static_cast<double>(usage.ru_maxrss - before) * 1024.0 / n);
}

} // namespace

int main(int argc, char** argv) {
    memoryFigure();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    auto const s = g_nsPerParticleStep.find("sparse"), l = g_nsPerParticleStep.find("large");
    if (s != g_nsPerParticleStep.end() && l != g_nsPerParticleStep.end())
        std::printf("detection + contacts: sparse gas %.1f ns/particle-step, with radius-30 "
                    "sphere %.1f ns/particle-step, ratio %.2f (target <= 1.5)\n",
                    s->second, l->second, l->second / s->second);
    return 0;
}
