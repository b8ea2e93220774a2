#pragma once
/// The scene's [[insert]] entries during the run: every `every` steps a batch of grains placed
/// without overlap in the entry's region (particles::placeBatch) joins the masters.
#include "apps/regolith/BlockPlacement.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <vector>

namespace regolith::apps {

/// The schedule and progress of the [[insert]] entries. Batch b of an entry falls after step
/// b x every and brings the entry's total to b x batchSize (at most count); grains that did not
/// fit wait for the next batch. Inserted grains have uids particles::insertedUid(entry, n),
/// n = 0, 1, ... in order, so a restart continues from the largest uid among the masters.
class GrainPouring {
public:
    /// Checks every entry's batch density (checkBatchDensity, with scene.time.dt resolved) and
    /// counts the grains already inserted (a restart's). COLLECTIVE.
    GrainPouring(core::Comm const& comm, SceneDescription const& scene,
                 particles::LocalParticles const& local);

    /// Whether a batch falls after step `stepsDone` (the same on every rank).
    [[nodiscard]] bool due(std::int64_t stepsDone) const;

    /// Places the batches due after step `stepsDone` around the masters of `placement` and
    /// the `walls` as they stand, and makes the new grains masters (every master moves to a
    /// fresh LocalParticles, as in a rebalance: the synchronisation and DemStep must then be
    /// relocated). Returns whether any grain was added. COLLECTIVE.
    bool afterStep(std::int64_t stepsDone, coupling::Placement& placement,
                   particles::WallList const& walls);

    /// Grains inserted by this invocation, over all ranks.
    [[nodiscard]] std::int64_t inserted() const { return m_inserted; }

private:
    core::Comm const* m_comm;
    SceneDescription const* m_scene;
    std::vector<std::int64_t> m_batch; ///< per entry, the grains one batch brings
    std::vector<std::int64_t> m_next;  ///< per entry, the next grain's number
    std::vector<bool> m_warnedShort;   ///< per entry, whether a batch short of room was reported
    std::int64_t m_inserted = 0;
};

} // namespace regolith::apps
