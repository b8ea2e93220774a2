#pragma once
/// A forest too coarse for the requested accuracy: the grid methods' force error
/// is set by the grid spacing relative to the body, so a scene that asks for a
/// gravity.accuracy the mesh cannot give on its domain.cells_per_block is refused before the
/// run, naming the cells per block it would need.
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <span>
#include <string_view>

namespace regolith::apps {

/// One measured point: the median relative force error against the direct sum at a number of
/// grid cells across the body (its largest bounding-box extent / h).
struct GridErrorPoint {
    double cellsAcrossBody;
    double medianError;
};

/// Measured on the second paper's 38,358-grain agglomerate (radii 20–60 m, TSC, 4th-order
/// gradient, rtol 1e-5, domain 1.2 body radii wide on each side; `grid_agglomerate_bench
/// --cells 32,64,128 --cutoffs 2,4`, docs/results.md), ascending cells across the body.
/// "pm": grains deposited as volumes; its error falls with the spacing. "p3m": the default
/// 4-cell cut-off; its error does not fall monotonically (a coarser grid corrects more pairs
/// exactly, a finer one resolves more with the mesh). Other bodies differ (the error also
/// depends on how many grains share a cell), so the check is a guide of the right order, not
/// a guarantee.
inline constexpr GridErrorPoint kMeshErrors[] = {{26.7, 1.85e-2}, {53.3, 1.12e-2}, {106.7, 3.4e-3}};
inline constexpr GridErrorPoint kP3mErrors[] = {{26.7, 7.3e-4}, {53.3, 1.9e-3}, {106.7, 1.1e-3}};

/// The measured points of `method` (pm or p3m), empty for the other methods.
[[nodiscard]] std::span<GridErrorPoint const> gridErrorPoints(std::string_view method);

/// The median error expected at `cellsAcross` from `points`: log-log interpolation between
/// them; coarser than the first point, the first segment's trend but at least the first
/// point's error grown in proportion to the cell edge (P3M's first segment rises with the
/// cells, so its trend alone rated every coarser grid at the first point's 7.3e-4; measured
/// on cold-collapse, 6 and 2.9 cells across gave 4.5e-3 and 1.0e-2, a growth slightly faster
/// than linear); finer than the last, the last point (no better than measured).
[[nodiscard]] double expectedGridError(std::span<GridErrorPoint const> points, double cellsAcross);

/// For gravity.self = "pm" or "p3m" with gravity.accuracy given in the scene: throws
/// core::InputError (on every rank alike) if the grid is coarser than the measured points say
/// the accuracy needs, naming gravity.accuracy, domain.cells_per_block and the cells per block
/// needed (or, if no measured grid meets it, the best the method reached and what to use
/// instead). Does nothing otherwise. COLLECTIVE over `comm` (extent of the masters).
void checkGridAccuracy(core::Comm const& comm, particles::ParticleStorage const& masters,
                       SceneDescription const& scene);

/// Grains sampled by checkMeasuredGridAccuracy.
inline constexpr std::size_t kAccuracySample = 256;

/// After set-up, for pm or p3m with gravity.accuracy given in free space: the first field's
/// median force error measured on about kAccuracySample of the scene's own grains against the
/// direct sum (SelfGravityForces::sampledForceError). checkGridAccuracy's estimate comes from
/// another body, and P3M measured 2.4-5 times worse than it on a uniform cloud and on the
/// default scene's rubble piles. Throws core::InputError (on every rank alike) if it is
/// above the accuracy, naming gravity.accuracy and what to change. Periodic domains are not
/// checked (the direct sum has no images). COLLECTIVE (over the communicator of `gravity`).
void checkMeasuredGridAccuracy(coupling::SelfGravityForces const& gravity,
                               SceneDescription const& scene);

} // namespace regolith::apps
