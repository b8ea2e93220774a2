#pragma once
/// The generated grains as particles: masters in the particle storage, owned by the local
/// block that contains their centre, checked before the first step (issue: "bad input").
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <span>

namespace regolith::apps {

/// Masters for `grains` (each inside one of this rank's blocks, as generateLocalGrains
/// guarantees). Not collective.
[[nodiscard]] particles::ParticleStorage makeMasters(std::span<particles::GrainInit const> grains,
                                                     domain::BlockForest const& forest, int rank);

/// Refuses an initial state the contact model cannot simulate: a bad radius or mass, grains
/// overlapping by more than contact.initial_overlap (both uids named), a grain outside the
/// domain, and a time step above t_c / 10 unless time.allow_unstable (t_c from the contact
/// stiffness and the smallest mass). Throws the same core::InputError on every rank.
/// COLLECTIVE over `comm`.
void checkInitialState(core::Comm const& comm, particles::ParticleStorage const& ps,
                       SceneDescription const& scene);

} // namespace regolith::apps
