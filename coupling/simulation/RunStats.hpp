#pragma once
/// What a stretch of time steps did (Simulation::run), the same on every rank.
#include "core/mpi/CommCounters.hpp"
#include "core/timing/TimerReport.hpp"

#include <cstdint>
#include <string>

namespace regolith::coupling {

struct RunStats {
    std::int64_t steps = 0;
    /// The steps alone, from a barrier before the first to the end of the slowest rank's last
    /// [s], the observers' time included (output written during the run), as LAMMPS's "Loop
    /// time".
    double wallSeconds = 0.0;
    core::TimerReport timers;    ///< the step's phases (sync, contact, integrate), over ranks
    core::CommTotals comm;       ///< the synchronisation's traffic
    std::int64_t leftDomain = 0; ///< masters that left an open domain, over all ranks
    /// Of those, the masters that passed through a wall (DemStep::wallCrossings), over all
    /// ranks, and the first of them ("particle uid 7 at step 12 through walls[0]").
    std::int64_t leftThroughWalls = 0;
    std::string firstWallCrossing;
    std::int64_t listRebuilds = 0; ///< Verlet-list rebuilds, over all blocks and ranks
    std::int64_t listShifts = 0;   ///< Verlet-list shifts with the grains' drift, likewise
    double listSkin = 0.0;         ///< the largest over the ranks of DemStep::listSkin
};

} // namespace regolith::coupling
