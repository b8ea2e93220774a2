#pragma once
#include "particles/integration/TimeStepGuard.hpp"
/// The generated grains as particles: masters owned by the local block that contains their
/// centre, checked before the first step (bad input is refused), and the contact model,
/// integrator and walls of the scene for the time step.
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <span>

namespace regolith::apps {

/// The shortest contact duration among the masters of `ps` over all ranks, for the scene's
/// contact model (time-step guard and time.dt = "auto"). COLLECTIVE.
[[nodiscard]] particles::ContactTimeEstimate contactTime(core::Comm const& comm,
                                                         particles::ParticleStorage const& ps,
                                                         SceneDescription const& scene);

/// The material types of the scene: 0 to the largest type its [[particles]], [[walls]] and
/// [[insert]] name or [[materials]] defines, the size of the contact model's tables. Not
/// collective.
[[nodiscard]] std::size_t materialTypeCount(SceneDescription const& scene);

/// Appends `g` to `masters` as a master owned by (`rank`, the local block of `forest` that
/// contains its centre), for the checks of the initial state. Throws core::Error if no local
/// block contains it (generateLocalGrains gives each rank only grains of its blocks). Not
/// collective.
void addGeneratedMaster(particles::ParticleStorage& masters, particles::GrainInit const& g,
                        domain::BlockForest const& forest, int rank);

/// Adds every grain as a master to the local block containing its centre
/// (LocalParticles::addMaster). generateLocalGrains returns each grain of the scene on exactly
/// one rank, the one whose (half-open, space-tiling) block box holds its centre, so every
/// grain is added exactly once over all ranks. Throws core::Error (a one-rank internal error)
/// if a grain lies in no local block, core::Error from addMaster for a uid given twice. Not
/// collective.
void addMasters(particles::LocalParticles& local, std::span<particles::GrainInit const> grains);

/// Refuses an initial state the contact model cannot simulate: a bad radius or mass, grains
/// overlapping by more than contact.initial_overlap (both uids named; pairs on this rank),
/// a grain outside the domain, and a time step above t_c / 10 unless time.allow_unstable (t_c
/// from the contact stiffness and the smallest mass). Throws the same core::InputError on
/// every rank. Warns if a pair can touch through two periodic images at once while contacts
/// carry springs. COLLECTIVE over `comm`.
void checkInitialState(core::Comm const& comm, particles::ParticleStorage const& ps,
                       SceneDescription const& scene);

/// The overlap rule of checkInitialState for pairs on different ranks or across a periodic
/// boundary: after the first synchronisation and force computation, `contacts[b]` holds the
/// contacts local block b evaluated (DemStep::contacts(); every contact in exactly one list).
/// Throws on every rank the same core::InputError, for the pair with the smallest
/// (uid_i, uid_j) over all ranks, if a pair overlaps by more than `overlapTolerance` times the
/// smaller radius (pairs of two Fixed grains excepted). COLLECTIVE over `comm`.
void checkOverlapsAcrossBlocks(core::Comm const& comm, particles::LocalParticles const& local,
                               std::span<particles::ContactList const> contacts,
                               double overlapTolerance);

/// The scene's contact model: contact.model with the parameters of every pair of material
/// types mixed from the scene's materials (particles/kernels/MaterialMixing.hpp;
/// spring-dashpot: k_t = 2/7 k_n; Hertz: E* and G* from E and nu). Throws core::InputError
/// for a parameter out of range. Not collective.
[[nodiscard]] particles::AnyContactModel makeContactModel(SceneDescription const& scene);

/// time.integrator: velocity Verlet or semi-implicit Euler. Not collective.
[[nodiscard]] particles::AnyIntegrator makeIntegrator(SceneDescription const& scene);

/// The scene's [[walls]] in order (uid = wallUid(index)). Not collective.
[[nodiscard]] particles::WallList makeWalls(SceneDescription const& scene);

} // namespace regolith::apps
