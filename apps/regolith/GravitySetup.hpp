#pragma once
/// The scene's [gravity] self = ... as the time step's body forces (coupling/).
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "domain/BlockForest.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <memory>

namespace regolith::apps {

/// The self-gravity of `scene` on the grains, or nullptr for self = "none". Throws
/// core::InputError naming gravity.self for a method the time step cannot use yet, and the
/// gravity.* key of a bad parameter (theta, G, softening, update_threshold). COLLECTIVE.
[[nodiscard]] std::unique_ptr<coupling::SelfGravityForces>
makeSelfGravity(core::Comm const& comm, domain::BlockForest const& forest,
                SceneDescription const& scene);

/// Warns (rank 0, once) when gravity.update_threshold exceeds the grain spacing, taken as the
/// smallest grain diameter over all ranks, stating the force error to expect
/// (gravity::UpdatePolicy::thresholdWarning). COLLECTIVE when self-gravity is on.
void warnLazyUpdateThreshold(core::Comm const& comm, particles::ParticleStorage const& masters,
                             SceneDescription const& scene);

} // namespace regolith::apps
