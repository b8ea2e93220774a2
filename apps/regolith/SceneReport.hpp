#pragma once
/// The reports `regolith` prints on rank 0: the scene before the run, the outcome after it.
#include "apps/common/RunSummary.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/app/RunApp.hpp"
#include "core/timing/TimerReport.hpp"
#include "domain/BlockForest.hpp"

#include <cstddef>
#include <cstdint>

namespace regolith::apps {

/// The particle counts of the initial state, over all ranks.
struct ParticleCounts {
    std::int64_t total = 0; ///< masters over all ranks
    std::int64_t minPerRank = 0;
    std::int64_t maxPerRank = 0;
};

/// The particle counts of all ranks from this rank's `local` count. COLLECTIVE over `comm`.
[[nodiscard]] ParticleCounts countParticles(core::Comm const& comm, std::int64_t local);

/// Prints the scene, domain, blocks (and how many subdomains the particles run on, over all
/// ranks), time/sync/contact/gravity settings and the particle counts to stdout. Call on one
/// rank (rank 0). Not collective.
void printSceneReport(core::AppContext const& ctx, SceneDescription const& scene,
                      domain::BlockForest const& forest, std::size_t particleSubdomains,
                      ParticleCounts const& particles, std::int64_t startStep = 0);

/// Prints what the time loop did: steps, loop time and PUpCS, final particle and shadow
/// counts, masters that left the domain, traffic per step, and the phase timers reduced over
/// ranks. Call on one rank (rank 0). Not collective.
void printRunReport(RunSummary const& summary, std::int64_t leftDomain,
                    core::TimerReport const& timers);

} // namespace regolith::apps
