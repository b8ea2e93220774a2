#pragma once
/// The initial state of a run, from the scene's [[particles]] entries: every rank generates
/// the grains whose centre lies in its own blocks, without communication.
#include "apps/common/MasterRecord.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace regolith::apps {

/// The grains of `scene.particles` whose centre lies in one of this rank's blocks, sorted by
/// uid: particles::generateGrains with the local blocks' boxes. Block boxes are half-open and
/// tile the domain, and the generation is deterministic and rank-independent, so every grain
/// of the whole-domain generation is on exactly one rank, with the same uid and bit-identical
/// values whatever the number of ranks and blocks. An idle rank gets none (and still takes
/// part in the agreement).
///
/// Errors: a core::InputError of the generation on any rank (a particle file unreadable on
/// some node, an agglomerate that cannot be packed, ...) is thrown on every rank with the
/// lowest failing rank's message (agreeOnInputError), prefixed with where the scene key it
/// names was written (locateSceneKey on `sceneRoot`, the scene that `scene` was parsed from).
/// COLLECTIVE over `comm` (the forest's communicator).
[[nodiscard]] std::vector<particles::GrainInit>
generateLocalGrains(core::Comm const& comm, core::ConfigTable const& sceneRoot,
                    SceneDescription const& scene, domain::BlockForest const& forest);

/// The grains of generateLocalGrains, in the same order, passed one by one to `sink` (same
/// rules and errors; COLLECTIVE). The list form above holds every grain as a 112-byte record.
void generateLocalGrains(core::Comm const& comm, core::ConfigTable const& sceneRoot,
                         SceneDescription const& scene, domain::BlockForest const& forest,
                         particles::GrainSink const& sink);

/// The grains of generateLocalGrains as masters in one storage (each owned by the local
/// block containing its centre), for the checks of the initial state. Memory: the scene is
/// generated twice, once to count the grains and once to store them into arrays reserved to
/// exactly that count, so no grain is ever held twice (record list + storage) and no array
/// carries the slack of doubling growth; the set-up's peak is the storage itself. Throws as
/// generateLocalGrains, and core::Error if a grain lies in no local block. COLLECTIVE.
[[nodiscard]] particles::ParticleStorage generateLocalMasters(core::Comm const& comm,
                                                              core::ConfigTable const& sceneRoot,
                                                              SceneDescription const& scene,
                                                              domain::BlockForest const& forest);

/// The grains as reported masters (uid, position, velocities, radius, mass), same order.
/// Not collective.
[[nodiscard]] std::vector<MasterRecord>
toMasterRecords(std::span<particles::GrainInit const> grains);

/// How many of `masters` overlap one of `walls` (signed distance of the centre from the
/// wall below the radius; touching is no overlap). Not collective.
[[nodiscard]] std::int64_t countWallOverlaps(MasterSource const& masters,
                                             std::span<particles::Wall const> walls);

} // namespace regolith::apps
