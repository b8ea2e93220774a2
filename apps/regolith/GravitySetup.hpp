#pragma once
/// The scene's [gravity] self = ... as the time step's body forces (coupling/).
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "domain/BlockForest.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

namespace regolith::apps {

/// The median error an adaptive update interval leaves to the extrapolation between updates
/// (at the stalest step), when the method's own median error is `methodError`: what is left of
/// kErrorTarget x `accuracy` (AutoChoices.hpp) as the two add in quadrature (independent
/// directions), sqrt((kErrorTarget accuracy)² - methodError²), and at least
/// kMinExtrapolationShare x accuracy. Not collective.
[[nodiscard]] double extrapolationBudget(double accuracy, double methodError);
/// The same for the scene's method: the tree's error interpolated in θ from kTreeErrors (its
/// nearest point beyond them), 0 for the direct sum, half of the target for the others (their
/// error depends on the grid; the run's measured error tells).
[[nodiscard]] double extrapolationBudget(GravitySection const& g);

inline constexpr double kMinExtrapolationShare = 0.25;

/// gravity.update_every as the update policy's interval (dt from time.dt; "adaptive" starts at
/// one step and aims at extrapolationBudget). Not collective.
[[nodiscard]] gravity::UpdateInterval updateInterval(SceneDescription const& scene);

/// Checks of the measured force error a run with gravity.check_every = "auto" takes.
inline constexpr std::int64_t kAutoChecksPerRun = 8;

/// When the run measures the force error its grains feel (gravity.check_every; "auto": one check
/// in each kAutoChecksPerRun-th of time.steps; none in a periodic domain, where the direct sum
/// lacks the images). Throws core::InputError naming the key for a count > 0 in a periodic
/// domain. Not collective.
[[nodiscard]] coupling::ForceCheckSchedule forceCheckSchedule(SceneDescription const& scene);

/// Empty, or the warning for a run whose measured median force error (checks > 0) exceeds
/// kMeasuredErrorTolerance x gravity.accuracy, naming what to change: the update threshold
/// when the field was reused between updates (`updates` < `steps`), the method's own
/// accuracy (theta, the grid) otherwise. Not collective.
[[nodiscard]] std::string measuredErrorWarning(coupling::ForceErrorMonitor const& measured,
                                               SceneDescription const& scene, long long updates,
                                               long long steps);

inline constexpr double kMeasuredErrorTolerance = 2.0;

/// The self-gravity of `scene` on the grains (its registered method, coupling/gravity/
/// GravityMethod.hpp), or none for self = "none". Throws core::InputError naming gravity.self
/// for "auto" not resolved yet; the SelfGravityForces built from it name the gravity.* key of
/// a bad parameter (theta, G, softening, update_threshold, the method's own). Not collective.
[[nodiscard]] std::optional<coupling::SelfGravityConfig>
selfGravityConfig(SceneDescription const& scene);

/// The warnings below about the self-gravity parameters against the grains, for a new run's
/// masters and for a restart's (which may change G, contact.stiffness, time.dt or
/// gravity.update_threshold). `local`: this rank's blocks with their masters. COLLECTIVE when
/// self-gravity is on.
void warnSelfGravityParameters(core::Comm const& comm, particles::LocalParticles const& local,
                               SceneDescription const& scene);

/// Warns (rank 0, once) when gravity.update_threshold exceeds the grain spacing, taken as the
/// smallest grain diameter over all ranks, stating the force error to expect
/// (gravity::UpdatePolicy::thresholdWarning). COLLECTIVE when self-gravity is on.
void warnLazyUpdateThreshold(core::Comm const& comm, particles::LocalParticles const& local,
                             SceneDescription const& scene);

/// Warns (rank 0, once) when the linear contacts are too soft for the grains' own gravity: two
/// touching grains overlap at rest by G m² / (2r)² / k under their mutual attraction alone;
/// above kSoftContactOverlap of the radius for the grain with the largest m² / r³ (a pile's
/// weight adds to it, impacts more). Without it, grains of cold-collapse sank 1.5 radii into
/// each other, and a pair with G 10⁴ times larger passed through each other and was
/// ejected (point-mass gravity inside an overlap). COLLECTIVE when self-gravity is on.
void warnSoftContacts(core::Comm const& comm, particles::LocalParticles const& local,
                      SceneDescription const& scene);

/// The static pair overlap, over the radius, above which warnSoftContacts warns.
inline constexpr double kSoftContactOverlap = 0.1;

/// With self-gravity, warns if time.dt exceeds the orbital period of two touching grains of
/// the largest density, 2 pi sqrt(3 / (pi G rho)), over kOrbitSteps: a close orbit then takes
/// fewer steps than that and its energy is not kept (time.dt = "auto" takes the period / 200).
/// The contact guard (t_c / 10) does not see it when contacts are soft: a Kepler pair at
/// dt = T / 2.2 was ejected without a word. COLLECTIVE when self-gravity is on.
void warnCoarseOrbitStep(core::Comm const& comm, particles::LocalParticles const& local,
                         SceneDescription const& scene);

inline constexpr double kOrbitSteps = 20.0;

/// The orbital period of two touching spheres of density `density` under G:
/// 2 pi sqrt((2r)^3 / (G 2m)) = 2 pi sqrt(3 / (pi G rho)) [time].
[[nodiscard]] inline double touchingOrbitPeriod(double G, double density) {
    return 2.0 * std::numbers::pi * std::sqrt(3.0 / (std::numbers::pi * G * density));
}

} // namespace regolith::apps
