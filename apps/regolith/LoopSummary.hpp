#pragma once
/// What the run summary of `regolith` reports about the time steps, and the grains as records.
#include "apps/common/MasterRecord.hpp"
#include "apps/common/RunSummary.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/simulation/RunStats.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <vector>

namespace regolith::apps {

/// The masters of every local block as reported records (block order, then storage order).
/// Not collective.
[[nodiscard]] std::vector<MasterRecord> masterRecords(particles::LocalParticles const& local);
/// The same records as a source, read from the storages when visited (`local` must outlive
/// it). Not collective.
[[nodiscard]] MasterSource masterSource(particles::LocalParticles const& local);

/// Fills the loop's keys of `summary`: steps, wall_s, timing_s (average over ranks of each
/// phase, gravity from the body-force timer), comm (messages and bytes summed over ranks per
/// step, the largest number of peers of one exchange), left_domain, neighbour_list, and the
/// final global counts of masters (particles) and shadow copies (shadows) in `local`.
/// COLLECTIVE over `comm`.
void fillLoopSummary(core::Comm const& comm, coupling::RunStats const& loop,
                     particles::LocalParticles const& local, RunSummary& summary);

} // namespace regolith::apps
