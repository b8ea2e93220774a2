#pragma once
/// Dynamic load balancing ([balance]): every `every` steps the ranks measure their loads (the
/// grains and grid cells of the blocks they own: coupling/balance/BlockWeights.hpp) and agree
/// on the imbalance, max / mean. Above the threshold the blocks are re-cut along the Hilbert
/// curve by those loads (balanceByLoad), if the new cut lowers the imbalance by at least half
/// of (threshold - 1): the hysteresis that keeps a borderline run from moving blocks at every
/// measurement. The grains move with their complete state, as a restart's do, so a run that
/// rebalances continues bit for bit in reproducible mode; what stands on the old assignment
/// (the synchronisation, the contact lists, a gravity grid) the caller's `relocate` rebuilds.
/// With `every` = 0 the loads are still measured, every autoBalanceEvery(time.steps) steps,
/// for the run summary; with "auto" the interval adapts (autoBalanceEvery).
#include "apps/common/RunSummary.hpp"
#include "apps/regolith/BlockPlacement.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/balance/BlockWeights.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace regolith::apps {

/// The shortest interval of balance.every = "auto" [steps].
inline constexpr std::int64_t kShortestAutoInterval = 10;

/// balance.every = "auto" on more than one rank, and the measuring interval of a run that
/// does not rebalance [steps]: 20 measurements in a run of `steps`, between 10 and 100 steps
/// apart. With "auto" this is the longest interval: after a rebalance the next measurement
/// comes after half the interval (at least kShortestAutoInterval), after an even measurement
/// after twice it, so that a load that moves fast (a gas landing on a floor) is followed
/// closely and a steady one costs 20 measurements. A measurement costs a count of the masters
/// and two all-reductions (below 1 % of a step at these intervals); a rebalance, when the
/// loads differ, a few steps' time.
[[nodiscard]] constexpr std::int64_t autoBalanceEvery(std::int64_t steps) {
    return std::clamp<std::int64_t>(steps / 20, kShortestAutoInterval, 100);
}

class DynamicBalance {
public:
    /// What the balance asks of the run it balances.
    struct RunHooks {
        /// Each copy's contacts of the last step (DemStep::contactsOfLastPass). Local.
        std::function<particles::ContactCounts()> contacts;
        /// Completes a step that ended Open (DemStep::completeStep), before the grains move.
        std::function<void()> completeStep;
        /// Rebuilds what stands on the blocks' assignment after the grains moved. COLLECTIVE.
        std::function<void()> relocate;
    };

    /// `placement` is the run's (its objects are replaced in place when the blocks move);
    /// the run starts after `stepsDone` steps.
    DynamicBalance(core::Comm const& comm, SceneDescription const& scene,
                   coupling::Placement& placement, std::int64_t stepsDone, RunHooks hooks);

    /// Whether the loads are measured after the step that leaves `stepsDone` steps done. The
    /// step may end Open: a measurement reads the grains' positions and the contacts of the
    /// last step (RunHooks::contacts), and completes the step before it moves grains.
    [[nodiscard]] bool due(std::int64_t stepsDone) const;
    /// Measures the imbalance, and rebalances if the scene asks and the imbalance is over the
    /// threshold (see the file comment). Returns whether the blocks moved. COLLECTIVE.
    bool afterStep(std::int64_t stepsDone);
    /// The last measured imbalance (1 before the first measurement).
    [[nodiscard]] double imbalance() const { return m_last; }
    /// Measures the final imbalance and returns what the run summary reports. COLLECTIVE.
    [[nodiscard]] RunSummary::Balance finish();

private:
    /// Each copy's contacts of the last step (RunHooks::contacts); none on one rank. Local.
    [[nodiscard]] particles::ContactCounts lastContacts() const;
    /// The spread of the ranks' loads now, with `contacts` (lastContacts). COLLECTIVE.
    [[nodiscard]] coupling::LoadSpread measure(particles::ContactCounts const& contacts) const;
    bool measureAndMove(std::int64_t stepsDone);

    core::Comm const* m_comm;
    SceneDescription const* m_scene;
    coupling::Placement* m_placement;
    RunHooks m_hooks;
    std::int64_t m_longest;  ///< balance.every, or the interval of the measurements
    std::int64_t m_interval; ///< the current one (below m_longest with "auto" after a move)
    std::int64_t m_next;     ///< the step after which the next measurement comes
    std::int64_t m_start;    ///< steps done when the run started
    double m_last = 1.0;
    double m_floor = 1.0; ///< the largest LoadSpread::blockFloor measured (after the splits)
    bool m_warned = false;
    double m_seconds = 0.0;
    long long m_rebalances = 0;
    std::vector<double> m_steps, m_imbalances; ///< the measurements
};

} // namespace regolith::apps
