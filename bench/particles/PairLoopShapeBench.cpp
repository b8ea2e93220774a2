// What a pair loop shaped like LAMMPS's costs on this machine with Regolith's own contact
// model: the floor against which the fused contact loop (ContactDetector::listedPass +
// BatchedSpringDashpot) is judged (docs/notes/contact-loop.md).
//
// The MESA-PD "GranularGas" geometry of bench/peers/lammps_compare.py's `mesapd` case: an
// n^3 simple-cubic lattice, spacing 1, radius 0.6, periodic, every sphere overlapping its six
// neighbours. The loop is LAMMPS's (pair gran/hooke/history, newton on): a half neighbour list
// in compressed rows (each grain's +x, +y, +z neighbours), the tangential springs in a flat
// array beside it, grain i's state and force in registers over its row, j's force and torque
// scattered per pair. Each contact is SpringDashpot::operator() on a ContactState built as
// pairState builds it. No detection, synchronisation or integration: the pair loop alone.
//
//   particles_bench --benchmark_filter=scalarPairLoop
// Argument: 0 = grains at rest (as the comparison), 1 = small random velocities and spins.
//
// batchedPairLoop: the same list through the project's own batched kernel
// (SpringDashpotBatch, 64 contacts per batch, the shares scattered as DemStep's sink does),
// with the tangential springs either in a flat array in list order beside the list
// (argument 0, LAMMPS's `fix neigh/history` layout) or in the grains' ContactHistory, found
// through the one-byte hint kept per listed pair (argument 1, BatchedSpringDashpot as DemStep
// runs it). No detection or overlap test (every listed pair overlaps), synchronisation or
// integration: what the kernel and the springs' place cost per pair.
//
//   particles_bench --benchmark_filter=batchedPairLoop
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/SpringDashpotBatch.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "bench/particles/OneMaterial.hpp"

namespace {

using namespace regolith::particles;
using regolith::core::Vec3;

struct Lattice {
    std::vector<Vec3> x, v, w, f, t;
    std::vector<double> radius, invMass;
    std::vector<std::uint32_t> rowStart, neighbour; ///< half list, compressed rows
    std::vector<Vec3> shift;                        ///< per listed pair: periodic shift of j
};

Lattice lattice(int n, double r, bool moving) {
    Lattice l;
    std::size_t const grains = static_cast<std::size_t>(n) * n * n;
    double const mass = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    auto index = [n](int a, int b, int c) {
        return static_cast<std::uint32_t>((a * n + b) * n + c);
    };
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            for (int c = 0; c < n; ++c) {
                l.x.emplace_back(a + 0.5, b + 0.5, c + 0.5);
                l.v.push_back(moving ? Vec3(u(rng), u(rng), u(rng)) : Vec3::Zero());
                l.w.push_back(moving ? Vec3(u(rng), u(rng), u(rng)) : Vec3::Zero());
                l.radius.push_back(r);
                l.invMass.push_back(1.0 / mass);
                l.rowStart.push_back(static_cast<std::uint32_t>(l.neighbour.size()));
                for (std::array<int, 3> const& d :
                     {std::array{1, 0, 0}, std::array{0, 1, 0}, std::array{0, 0, 1}}) {
                    std::array<int, 3> m{a + d[0], b + d[1], c + d[2]};
                    Vec3 s = Vec3::Zero();
                    for (int k = 0; k < 3; ++k)
                        if (m[k] == n) {
                            m[k] = 0;
                            s[k] = n;
                        }
                    l.neighbour.push_back(index(m[0], m[1], m[2]));
                    l.shift.push_back(s);
                }
            }
    l.rowStart.push_back(static_cast<std::uint32_t>(l.neighbour.size()));
    l.f.assign(grains, Vec3::Zero());
    l.t.assign(grains, Vec3::Zero());
    return l;
}

void scalarPairLoop(benchmark::State& state) {
    Lattice l = lattice(30, 0.6, state.range(0) != 0);
    SpringDashpot const model = regolith::bench::oneMaterialSpringDashpot(50.0, 0.9, 0.5);
    double const dt = 0.01;
    std::vector<Vec3> spring(l.neighbour.size(), Vec3::Zero());
    Vec3 rolling = Vec3::Zero(); // model A: untouched
    std::size_t const grains = l.x.size();
    for (auto _ : state) {
        for (std::size_t i = 0; i < grains; ++i)
            l.f[i] = l.t[i] = Vec3::Zero();
        for (std::size_t i = 0; i < grains; ++i) {
            Vec3 const xi = l.x[i], vi = l.v[i], wi = l.w[i];
            double const a = l.radius[i], invMi = l.invMass[i];
            Vec3 fi = Vec3::Zero(), ti = Vec3::Zero();
            for (std::uint32_t q = l.rowStart[i]; q < l.rowStart[i + 1]; ++q) {
                std::uint32_t const j = l.neighbour[q];
                Vec3 const xj = l.x[j] + l.shift[q];
                double const b = l.radius[j];
                Vec3 const d = xj - xi;
                double const dist = d.norm();
                if (!(dist < a + b)) {
                    spring[q].setZero();
                    continue;
                }
                // overlapGeometry and pairState, with i's values from registers.
                Vec3 const normal = d / dist;
                double const pen = (a + b) - dist;
                Vec3 const point = xi + (a - 0.5 * pen) * normal;
                Vec3 const ri = point - xi, rj = point - xj;
                ContactState const s{normal,
                                     pen,
                                     Vec3((l.v[j] + l.w[j].cross(rj)) - (vi + wi.cross(ri))),
                                     Vec3(l.w[j] - wi),
                                     1.0 / (invMi + l.invMass[j]),
                                     a * b / (a + b),
                                     0.0,
                                     0,
                                     0};
                ContactResponse const r = model(s, spring[q], rolling, dt);
                l.f[j] += r.force;
                l.t[j] += rj.cross(r.force) + r.torque;
                fi -= r.force;
                ti -= ri.cross(r.force) + r.torque;
            }
            l.f[i] += fi;
            l.t[i] += ti;
        }
        benchmark::DoNotOptimize(l.f.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(l.neighbour.size()));
    state.counters["pairs"] = static_cast<double>(l.neighbour.size());
}
BENCHMARK(scalarPairLoop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void batchedPairLoop(benchmark::State& state) {
    bool const springsInGrains = state.range(0) != 0;
    Lattice const l = lattice(30, 0.6, false);
    ParticleStorage ps;
    for (std::size_t i = 0; i < l.x.size(); ++i) {
        ParticleInit p;
        p.uid = static_cast<Uid>(i + 1);
        p.position = l.x[i];
        p.radius = l.radius[i];
        p.mass = 1.0 / l.invMass[i];
        ps.add(p);
    }
    std::size_t const pairs = l.neighbour.size();
    std::vector<std::uint32_t> first(pairs); // i of each listed pair
    for (std::size_t i = 0; i + 1 < l.rowStart.size(); ++i)
        for (std::uint32_t q = l.rowStart[i]; q < l.rowStart[i + 1]; ++q)
            first[q] = static_cast<std::uint32_t>(i);
    auto pairAt = [&](std::size_t q) { return PairOverlap{first[q], l.neighbour[q], l.shift[q]}; };
    SpringDashpot const model = regolith::bench::oneMaterialSpringDashpot(50.0, 0.9, 0.5);
    double const dt = 0.01;
    auto sink = [&ps](std::size_t k, Uid, Vec3 const& f, Vec3 const& t) {
        ps.force(k) += f;
        ps.torque(k) += t;
    };
    SpringDashpotBatch batch;
    std::vector<HistoryEntry> beside(pairs);
    std::vector<std::uint8_t> hints(pairs, 0);
    std::uint32_t stamp = 0;
    for (auto _ : state) {
        ps.resetForces();
        ++stamp;
        if (springsInGrains) {
            BatchedSpringDashpot loop(ps, model, dt, stamp, batch, sink);
            for (std::size_t q = 0; q < pairs; ++q)
                loop(pairAt(q), hints[q]);
            loop.finish();
            continue;
        }
        auto flush = [&] {
            batch.evaluate(ps, model, dt);
            for (std::size_t k = 0; k < batch.size(); ++k) {
                batch.entry(k)->spring = batch.spring(k);
                Vec3 const f = batch.force(k);
                sink(batch.j(k), 0, f, batch.torqueJ(k));
                sink(batch.i(k), 0, Vec3(-f), Vec3(-batch.torqueI(k)));
            }
            batch.clear();
        };
        batch.clear();
        for (std::size_t q = 0; q < pairs; ++q) {
            if (batch.full())
                flush();
            batch.add(pairAt(q), beside[q], 0);
        }
        flush();
    }
    benchmark::DoNotOptimize(ps.force(0));
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(pairs));
    state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(batchedPairLoop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

} // namespace
