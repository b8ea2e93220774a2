// The spring-dashpot batch kernel alone (SpringDashpotBatch::evaluate), per contact: the
// arithmetic of the fused contact loop, with its loads of the grains' state, without its history
// look-ups and scatters, with or without collecting the pairs (add), on 64 contacts that stay
// in L1. Moving: half of the contacts slide (Coulomb limit), half stick, all carry a spring from
// earlier steps, so that every branch of the scalar model is exercised. At rest: the grains do
// not move and no contact carries a spring, as in the static lattice of lammps_compare.py's
// mesapd case (the lanes then skip the projection and the slider).
//
//   particles_bench --benchmark_filter=springDashpotBatch
#include "particles/kernels/SpringDashpotBatch.hpp"

#include <benchmark/benchmark.h>

#include <numbers>
#include <random>
#include <vector>

#include "bench/particles/OneMaterial.hpp"

namespace {

using namespace regolith::particles;
using regolith::core::Vec3;

void springDashpotBatch(benchmark::State& state) {
    constexpr std::size_t kContacts = SpringDashpotBatch::kCapacity;
    constexpr double kRadius = 0.5;
    double const mass = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;
    ParticleStorage ps;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    UidGenerator uids(0);
    bool const moving = state.range(1) != 0;
    // Pairs (2k, 2k + 1) overlapping by ~2 % of the radius in a random direction.
    for (std::size_t k = 0; k < kContacts; ++k) {
        Vec3 const x(3.0 * static_cast<double>(k), 0.0, 0.0);
        Vec3 const n = Vec3(u(rng), u(rng), u(rng)).normalized();
        for (int side = 0; side < 2; ++side) {
            ParticleInit p;
            p.uid = uids.next();
            p.position = side == 0 ? x : Vec3(x + (2.0 * kRadius - 0.02 * kRadius) * n);
            p.velocity = moving ? Vec3(0.1 * Vec3(u(rng), u(rng), u(rng))) : Vec3::Zero();
            p.angularVelocity = moving ? Vec3(0.1 * Vec3(u(rng), u(rng), u(rng))) : Vec3::Zero();
            p.radius = kRadius;
            p.mass = mass;
            ps.add(p);
        }
    }
    SpringDashpot const model = regolith::bench::oneMaterialSpringDashpot(2000.0, 0.5, 0.5);
    // Springs: the sticking half small, the sliding half far beyond mu F_n / k_t.
    std::vector<HistoryEntry> entries(kContacts);
    for (std::size_t k = 0; k < kContacts; ++k)
        entries[k].spring =
            moving ? Vec3((k % 2 == 0 ? 1e-5 : 1e-1) * Vec3(u(rng), u(rng), u(rng))) : Vec3::Zero();
    SpringDashpotBatch batch;
    double const dt = 0.002;
    bool const gather = state.range(0) != 0;
    auto fill = [&] {
        batch.clear();
        for (std::size_t k = 0; k < kContacts; ++k)
            batch.add(PairOverlap{2 * k, 2 * k + 1, Vec3::Zero()}, entries[k], 0);
    };
    fill();
    for (auto _ : state) {
        if (gather) // else the springs evolve in the lanes from one evaluation to the next
            fill();
        batch.evaluate(ps, model, dt);
        benchmark::DoNotOptimize(batch.force(kContacts - 1));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kContacts));
}
// Arguments: 1 = collect the contacts (SpringDashpotBatch::add) before each evaluation, 0 = not;
// 1 = moving, 0 = at rest.
BENCHMARK(springDashpotBatch)->ArgsProduct({{0, 1}, {1, 0}});

} // namespace
