#pragma once
/// Synthetic bodies for tests, benchmarks and examples: a Plummer sphere (the standard N-body
/// accuracy test) and a packed agglomerate like the second paper's instances (3,866 /
/// 11,100 / 38,358 grains, radii 50–100, 35–70, 20–60 m, density 3,000 kg/m³).
#include "core/math/Vec3.hpp"
#include "gravity/common/PointMasses.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::gravity::samples {

/// Grains in SoA (m, kg, m); `view()` lends them to the kernels.
struct Body {
    std::vector<double> x, y, z, m, r;

    [[nodiscard]] std::size_t size() const { return x.size(); }
    [[nodiscard]] PointMasses view() const { return {x, y, z, m, r}; }
    /// Appends grain i of `other`.
    void push(Body const& other, std::size_t i);
};

/// n equal point masses (radius 0) drawn from a Plummer (1911) sphere of total mass
/// `totalMass` (kg) and scale radius `a` (m), cumulative mass M(r) = M r³/(r² + a²)^{3/2},
/// truncated at 10 a (mass fraction ≥ 0.985 kept); deterministic for `seed`. Not collective.
[[nodiscard]] Body plummerSphere(std::size_t n, double totalMass, double a, std::uint64_t seed);

/// n non-overlapping spheres with radii uniform in [rMin, rMax] m and density `density`
/// (kg/m³) packed by random sequential insertion (largest first) into a sphere about
/// `centre` whose radius gives the packing fraction `packing` (≤ 0.35 packs quickly).
/// Deterministic for `seed`. Throws core::InputError if a grain finds no place. Not
/// collective.
[[nodiscard]] Body packedAgglomerate(std::size_t n, double rMin, double rMax, double density,
                                     double packing, core::Vec3 const& centre, std::uint64_t seed);

/// The grains of `body` in
/// slab `part` of `parts` equal-count slabs along x (a stand-in for a block decomposition in
/// tests and benches). Not collective.
[[nodiscard]] Body slabOf(Body const& body, int part, int parts);

} // namespace regolith::gravity::samples
