#include "apps/regolith/DynamicBalance.hpp"

#include "coupling/balance/BlockWeights.hpp"

#include <mpi.h>

#include <algorithm>
#include <utility>

namespace regolith::apps {

DynamicBalance::DynamicBalance(core::Comm const& comm, SceneDescription const& scene,
                               BlockPlacement& placement, std::int64_t stepsDone, Relocate relocate)
    : m_comm(&comm)
    , m_scene(&scene)
    , m_placement(&placement)
    , m_relocate(std::move(relocate))
    , m_longest(scene.balance.every > 0 ? scene.balance.every : autoBalanceEvery(scene.time.steps))
    , m_interval(m_longest)
    , m_next((stepsDone / m_longest + 1) * m_longest)
    , m_start(stepsDone) {}

bool DynamicBalance::due(std::int64_t stepsDone) const {
    return stepsDone >= m_next;
}

bool DynamicBalance::afterStep(std::int64_t stepsDone) {
    if (!due(stepsDone))
        return false;
    bool const moved = measureAndMove(stepsDone);
    if (m_scene->balance.adapts) // sooner after a move, back to the longest when even
        m_interval = moved ? std::max(kShortestAutoInterval, m_interval / 2)
                           : std::min(m_longest, m_interval * 2);
    m_next = stepsDone + m_interval;
    return moved;
}

bool DynamicBalance::measureAndMove(std::int64_t stepsDone) {
    m_last = coupling::loadImbalance(*m_comm,
                                     coupling::rankLoad(*m_placement->local, loadModel(*m_scene)));
    m_steps.push_back(static_cast<double>(stepsDone));
    m_imbalances.push_back(m_last);
    BalanceSection const& balance = m_scene->balance;
    if (balance.every == 0 || !(m_last > balance.threshold))
        return false;
    double const started = MPI_Wtime();
    double const hysteresis = 0.5 * (balance.threshold - 1.0);
    BalanceOutcome const outcome =
        balanceByLoad(*m_comm, *m_scene, *m_placement, [hysteresis](double before, double after) {
            return after <= before - hysteresis;
        });
    if (outcome.moved) {
        m_relocate();
        ++m_rebalances;
    }
    m_seconds += MPI_Wtime() - started; // a cut not worth moving to costs its search
    return outcome.moved;
}

RunSummary::Balance DynamicBalance::finish() {
    RunSummary::Balance out;
    out.every = m_scene->balance.every;
    out.threshold = m_scene->balance.threshold;
    out.rebalances = m_rebalances;
    out.seconds = m_comm->allReduce(m_seconds, core::ReduceOp::Max);
    out.finalImbalance = coupling::loadImbalance(
        *m_comm, coupling::rankLoad(*m_placement->local, loadModel(*m_scene)));
    // The time average: each measurement stands for the steps since the one before it (with
    // "auto" they are closer while the blocks move).
    out.meanImbalance = out.finalImbalance;
    if (!m_imbalances.empty()) {
        double sum = 0.0;
        double previous = static_cast<double>(m_start);
        for (std::size_t k = 0; k < m_imbalances.size(); ++k) {
            sum += m_imbalances[k] * (m_steps[k] - previous);
            previous = m_steps[k];
        }
        out.meanImbalance = sum / (previous - static_cast<double>(m_start));
    }
    out.steps = m_steps;
    out.imbalances = m_imbalances;
    return out;
}

} // namespace regolith::apps
