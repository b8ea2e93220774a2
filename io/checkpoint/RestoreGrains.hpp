#pragma once
/// Putting the grains read from a checkpoint into the forest of the restarted run, which may
/// have another number of ranks than the run that wrote it.
#include "core/mpi/Comm.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <span>
#include <string>

namespace regolith::io {

/// Sends every grain of `grains` (this rank's slice of the file, any grains) to the rank
/// owning the block whose half-open box contains its (wrapped) centre, which adds it as a
/// master (LocalParticles::addMaster) with force, torque and contact history restored. The
/// owners are found from every rank's block boxes, gathered once (O(global blocks) memory)
/// and bucketed by root block;
/// the grains travel in one sparse exchange (NBX).
///
/// Pre: `local` holds no masters of these uids. Errors: a grain outside the domain of the
/// forest (the checkpoint was written for another domain) → core::InputError on every rank,
/// "<context>: grain uid U at [x, y, z] lies outside the scene's domain ..."; a grain no
/// block claims after wrapping → core::Error. COLLECTIVE over `comm` (the forest's).
void restoreGrains(core::Comm const& comm, particles::LocalParticles& local,
                   std::span<GrainState const> grains, std::string const& context);

} // namespace regolith::io
