#pragma once
/// The time-step loop of `regolith` and what the run summary reports about it.
#include "apps/common/MasterRecord.hpp"
#include "apps/common/RunSummary.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"
#include "core/timing/TimerReport.hpp"
#include "core/timing/TimerTree.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace regolith::apps {

/// What the loop did, the same on every rank.
struct LoopOutcome {
    std::int64_t steps = 0;
    /// The loop alone, from a barrier before the first step to the end of the slowest
    /// rank's last step [s] (set-up and output excluded, like LAMMPS's "Loop time").
    double wallSeconds = 0.0;
    core::TimerReport timers;    ///< the step's phases (sync, contact, integrate), over ranks
    core::CommTotals comm;       ///< the synchronisation's traffic during the loop
    std::int64_t leftDomain = 0; ///< masters that left an open domain, over all ranks
    /// Of those, the masters that passed through a wall (DemStep::wallCrossings), over all
    /// ranks, and the first of them ("particle uid 7 at step 12 through walls[0]").
    std::int64_t leftThroughWalls = 0;
    std::string firstWallCrossing;
    std::int64_t listRebuilds = 0; ///< Verlet-list rebuilds, over all blocks and ranks
    double listSkin = 0.0;         ///< the largest skin of the blocks' last rebuilds
};

/// Called after every step with the number of steps done (dem.stepsDone()): output,
/// checkpoints, progress. Must be collective-safe (called on every rank alike).
using AfterStep = std::function<void(std::int64_t stepsDone)>;

/// Whether afterStep(stepsDone) reads or writes the grains (output, a checkpoint). Must give
/// the same answer on every rank.
using ObservesStep = std::function<bool(std::int64_t stepsDone)>;

/// Runs `steps` steps of `dem` after forgetting the set-up's timers and traffic (so both
/// cover the loop only), calling `afterStep` (if set) after each; its time (output written
/// during the run) is part of wallSeconds, as in LAMMPS's loop time. A step after which
/// `observes` says nothing looks at the grains, and that is not the last, ends Open
/// (DemStep::StepEnd: its second half kick merged into the next step's first); without
/// `observes` every step ends Complete. The loop ends with the state complete. Pre:
/// dem.setUp() or dem.resume() was called; `dem` uses `sync` and `timers`.
/// COLLECTIVE over `comm` (the communicator `sync` was built from).
[[nodiscard]] LoopOutcome runTimeLoop(core::Comm const& comm, particles::DemStep& dem,
                                      particles::ParticleSync& sync, core::TimerTree& timers,
                                      std::int64_t steps, AfterStep const& afterStep = {},
                                      ObservesStep const& observes = {});

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
void fillLoopSummary(core::Comm const& comm, LoopOutcome const& loop,
                     particles::LocalParticles const& local, RunSummary& summary);

} // namespace regolith::apps
