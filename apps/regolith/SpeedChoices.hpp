#pragma once
/// The "auto" keys that change only the speed of a run, not its trajectory: sync.skin and
/// time.orientation (the default of both; [balance]'s are BalanceChoices.hpp's: in
/// reproducible mode a rebalance keeps every bit, otherwise it changes the order of sums as
/// another rank count does). Resolved on a new run and on a restart alike from
/// the grains and the outputs the scene writes, printed with the other "auto" choices and
/// listed in the run summary; checkpoints do not store them.
#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <vector>

namespace regolith::apps {

/// The sync skin "auto" takes, as a fraction of the smallest grain radius: the Verlet list's
/// default skin (DemStep), so that one decision of the shadows lasts about as long as a list.
inline constexpr double kAutoSyncSkinPerRadius = 0.25;

/// Resolves the speed keys of `scene` left "auto" (none with explicit values) and returns the
/// decisions:
///  - time.orientation: integrated where something reads it -- a checkpoint (or an HDF5
///    particle snapshot, output.dump_format) the run will
///    write (it stores the orientation), or semi-implicit Euler (which always integrates it);
///    the grains are
///    spheres, whose orientation no contact and no other output reads;
///  - sync.skin: kAutoSyncSkinPerRadius times the smallest grain radius over all ranks, for
///    methods "hybrid" and "nns" (0 for "sos"; 0 for "nns" where a grain's ball grown by it
///    would pass the edge of the blocks it may touch, which NNS would refuse).
/// `local` holds this rank's masters on the particles' subdomains. COLLECTIVE over `comm`.
[[nodiscard]] std::vector<AutoChoice> resolveSpeedChoices(core::Comm const& comm,
                                                          particles::LocalParticles const& local,
                                                          SceneDescription& scene);

} // namespace regolith::apps
