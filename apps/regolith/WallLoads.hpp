#pragma once
/// The walls' loads over all ranks: what the run summary (and any running output) reports per
/// wall.
#include "apps/common/RunSummary.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/storage/WallList.hpp"

#include <vector>

namespace regolith::apps {

/// Per wall of `walls`, in order: the force and torque (about its axis point) the grains
/// exerted in the last evaluation and the work it did on them since the start (or restart),
/// each the sum of every rank's share. The same on every rank. COLLECTIVE over `comm`.
[[nodiscard]] std::vector<RunSummary::Wall> reduceWallLoads(core::Comm const& comm,
                                                            particles::WallList const& walls);

} // namespace regolith::apps
