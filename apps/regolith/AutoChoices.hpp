#pragma once
/// "Model no more than the scene needs": the scene keys that may be "auto" —
/// gravity.self, gravity.update_threshold and time.dt — resolved from the grains and the
/// target accuracy, each with the reason, for the run report and the run summary.
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <string>
#include <vector>

namespace regolith::apps {

/// One decision: the key, the value chosen and why.
struct AutoChoice {
    std::string key;
    std::string value;
    std::string reason;
};

/// The median relative force error of the Barnes–Hut tree (quadrupoles, b_max + offset
/// opening) measured against the direct sum on the second paper's 38,358-grain agglomerate,
/// and the wall time of one evaluation there, one rank
/// (`gravity_bench --instances agg38358 --methods tree --thetas 0.3,0.4,0.5,0.6,0.7,0.9`,
/// docs/results.md; θ = 0.4's time, not quoted there, is the geometric mean of its neighbours').
struct TreeErrorPoint {
    double theta;
    double medianError;
    double wallMs;
};
inline constexpr TreeErrorPoint kTreeErrors[] = {{0.9, 5.2e-3, 29.2}, {0.7, 1.45e-3, 39.0},
                                                 {0.6, 9.2e-4, 44.8}, {0.5, 6.1e-4, 57.7},
                                                 {0.4, 2.9e-4, 87.1}, {0.3, 1.1e-4, 131.6}};

/// "auto" aims the run's measured median force error (method and extrapolation between
/// updates, GravitySetup.hpp's extrapolationBudget) at this share of gravity.accuracy.
inline constexpr double kErrorTarget = 0.9;

/// The relative cost per step of the tree at `p` with an adaptive update interval: one
/// evaluation per interval, and the interval grows as the square root of the extrapolation's
/// error budget (that error ∝ interval²): wallMs / sqrt(budget). +inf where the tree's own
/// error leaves no budget below kErrorTarget x `accuracy`.
[[nodiscard]] double treeCostPerStep(TreeErrorPoint const& p, double accuracy);

/// Below this many grains the direct sum (exact, O(N²)) costs about what the tree costs (3,866
/// grains: 23 ms direct vs 5 ms tree at θ = 0.5; the ratio grows as N).
inline constexpr long long kDirectSumMaxGrains = 2000;

/// The grid methods for "auto". P3M is considered only where it is safe — the scene
/// has a grid (domain.cells_per_block), the forest is unrefined and the domain free-space or
/// periodic on every axis — and meets gravity.accuracy by its measured error at the scene's
/// cells across the body (GridAccuracy.hpp); it is chosen only where it is also cheaper than the
/// tree. Measured side by side on the 38,358-grain agglomerate, one rank, CPU time
/// (`grid_agglomerate_bench --cells 32,64,128 --cutoffs 2,4 --thetas 0.5,0.7`,
/// docs/results.md): the tree 1.3 µs per grain at θ = 0.5 (0.9 at 0.7), P3M 4.4 µs per grain
/// at best (64³, 2-cell cut-off, at 3.4 times the tree's error). On that evidence P3M is not
/// chosen (the reason says so when it would have met the accuracy); the bare mesh never is
/// (its error, 3.4e-3 at best, misses what the tree meets faster).
inline constexpr double kTreeSecondsPerGrain = 1.3e-6;
inline constexpr double kP3mSecondsPerGrain = 4.4e-6;

/// Resolves every "auto" key of `scene` in place from `masters` (this rank's; counts and
/// extremes are reduced over ranks) and returns the decisions (empty if nothing was "auto"):
///  - gravity.self: "direct" for at most kDirectSumMaxGrains grains (or an accuracy finer
///    than the tree's best point), else "tree" with the θ of kTreeErrors of the least cost per
///    step together with the update interval (treeCostPerStep), or "p3m" where it is safe,
///    accurate enough and cheaper (see above);
///  - gravity.update_threshold: 0, and gravity.update_every (unless given) "adaptive": the
///    field extrapolated between updates, the interval following the measured extrapolation
///    error (kExtrapolationShare of gravity.accuracy, GravitySetup.hpp);
///  - time.dt: the smaller of t_c / 20 (contact duration) and T_orb / 200, the period of two
///    touching grains of the densest material orbiting each other, 2π sqrt(3 / (π G ρ)) (only
///    with self-gravity).
/// COLLECTIVE over `comm`.
[[nodiscard]] std::vector<AutoChoice> resolveAutoChoices(core::Comm const& comm,
                                                         particles::ParticleStorage const& masters,
                                                         SceneDescription& scene);

} // namespace regolith::apps
