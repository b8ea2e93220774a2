#include "apps/regolith/DynamicBalance.hpp"

#include "core/log/Log.hpp"
#include "domain/ForestBuilder.hpp"

#include <mpi.h>

#include <algorithm>
#include <utility>

namespace regolith::apps {

DynamicBalance::DynamicBalance(core::Comm const& comm, SceneDescription const& scene,
                               coupling::Placement& placement, std::int64_t stepsDone,
                               RunHooks hooks)
    : m_comm(&comm)
    , m_scene(&scene)
    , m_placement(&placement)
    , m_hooks(std::move(hooks))
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

particles::ContactCounts DynamicBalance::lastContacts() const {
    // One rank carries the mean load, and no block of it more: its spread is 1 and 1, uncounted.
    return m_comm->size() == 1 ? particles::ContactCounts{} : m_hooks.contacts();
}

coupling::LoadSpread DynamicBalance::measure(particles::ContactCounts const& contacts) const {
    if (m_comm->size() == 1)
        return {};
    particles::LocalParticles const& local = *m_placement->local;
    return coupling::loadSpread(*m_comm, local, contacts, loadModel(*m_comm, *m_scene, local));
}

bool DynamicBalance::measureAndMove(std::int64_t stepsDone) {
    particles::ContactCounts const contacts = lastContacts();
    coupling::LoadSpread const spread = measure(contacts);
    m_last = spread.imbalance;
    m_steps.push_back(static_cast<double>(stepsDone));
    m_imbalances.push_back(m_last);
    BalanceSection const& balance = m_scene->balance;
    if (balance.every == 0 || !(m_last > balance.threshold)) {
        m_floor = std::max(m_floor, spread.blockFloor);
        return false;
    }
    double const started = MPI_Wtime();
    // The grains may move: with their state whole. Completing the step moves no copy and
    // leaves each master's contacts as counted (DemStep::contactsOfLastPass), so the counts stay.
    m_hooks.completeStep();
    double const enough = m_last - 0.5 * (balance.threshold - 1.0); // the hysteresis
    std::size_t const blocks = m_placement->forest->globalBlockCount();
    double best = m_last; // the best cut's imbalance (this one's, if no other cut is found)
    bool const moved =
        balanceByLoad(*m_comm, *m_scene, *m_placement, contacts, [enough, &best](double after) {
            best = after;
            return after <= enough;
        });
    double floor = spread.blockFloor;
    if (moved) {
        m_hooks.relocate();
        ++m_rebalances;
        if (m_placement->forest->globalBlockCount() != blocks) // split: the new blocks' floor
            floor = measure(lastContacts()).blockFloor;
    }
    m_seconds += MPI_Wtime() - started; // a cut not worth moving to costs its search
    m_floor = std::max(m_floor, floor);
    if (best > balance.threshold && !m_warned) {
        m_warned = true; // once a run: the blocks are what the scene (and the splits) gave
        core::log::warn(
            "balance: at step {} no cut of the {} blocks brings the loads within "
            "balance.threshold = {}: the best leaves the busiest rank {:.2f} times the mean "
            "load (the heaviest block weighs {:.2f} times it){}. A finer domain.blocks, or a "
            "[[domain.refine]] box where the grains gather, does (docs/balance.md)",
            stepsDone, m_placement->forest->globalBlockCount(), balance.threshold, best, floor,
            balance.splitLevels > 0 ? ", and the blocks split no further (balance.split_levels, "
                                      "the grains' size, or the shadows a split would add)"
                                    : "");
    }
    return moved;
}

RunSummary::Balance DynamicBalance::finish() {
    RunSummary::Balance out;
    out.every = m_scene->balance.every;
    out.threshold = m_scene->balance.threshold;
    out.rebalances = m_rebalances;
    // Since the scene's forest (the start's cut may have split blocks too); a split adds seven.
    std::size_t const sceneBlocks = domain::ForestBuilder(m_scene->forest).leaves().size();
    out.splits =
        static_cast<long long>((m_placement->forest->globalBlockCount() - sceneBlocks) / 7);
    out.seconds = m_comm->allReduce(m_seconds, core::ReduceOp::Max);
    coupling::LoadSpread const last = measure(lastContacts());
    out.finalImbalance = last.imbalance;
    out.blockFloor = std::max(m_floor, last.blockFloor);
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
