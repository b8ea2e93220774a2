#pragma once
/// A global check of the state the shadow synchronisation (ParticleSync) promises after each
/// call, for tests and for debug builds (CMake option REGOLITH_CHECK_INVARIANTS). Every rank
/// sends a compact record of each copy it holds, and the boxes of its blocks, to rank 0,
/// which checks the whole picture and broadcasts the verdict. Cost: O(copies + blocks) bytes
/// gathered on rank 0 and O(masters x blocks touched) work there: a debugging aid, not for
/// production steps.
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::particles {

/// True in builds configured with -DREGOLITH_CHECK_INVARIANTS=ON (the debug presets), which
/// define the macro REGOLITH_CHECK_INVARIANTS for every target.
#if defined(REGOLITH_CHECK_INVARIANTS)
inline constexpr bool kCheckSyncInvariants = true;
#else
inline constexpr bool kCheckSyncInvariants = false;
#endif

/// At most this many violations are listed; the last line then says how many more there were.
inline constexpr std::size_t kMaxListedViolations = 100;

/// Checks the synchronisation invariants over all ranks and returns the violations found, one
/// line each (at most kMaxListedViolations plus a summary line), identical on every rank;
/// empty means the state is consistent. Checked:
///  1. every uid has exactly one master globally, and no shadow exists without one;
///  2. a master lies in its block (half-open box contains its position), has image 0 and
///     names its own (rank, block) as owner; every copy sits in a block of the forest owned by
///     the rank that holds it;
///  3. every shadow agrees bit for bit with its master in position, velocity, angular
///     velocity, orientation, radius and mass, and its owner names the master's block;
///  4. the master's shadowHolders() is sorted, unique and equal to the set of (rank, block,
///     image) where shadows of it exist (both directions);
///  5. every (block, image) of the forest where copyNeeded() holds for a master's canonical
///     position and radius holds exactly one copy (the master or a shadow), and no block holds
///     a copy where copyNeeded() is false -- for the radius plus twice `skin`, the sync skin
///     (SyncConfig::skin, UpdateList.hpp), under which a copy may outlive its need. Images are
///     enumerated from the ball's extent on periodic axes (so a block that is its own periodic
///     neighbour is covered).
///
/// Check 5 is exact for grains without Flag::Spreads (NNS class: Alg. 1 of Eibl & Ruede 2018
/// leaves no missing or stale copy after each call). For Flag::Spreads grains (SOS class,
/// Alg. 2) copies spread one block layer per call, so check 5 applies to them only if
/// `spreadingConverged` (after ParticleSync::syncUntilConverged, and after every following
/// single call per step). Decisions within a relative 1e-12 of the overlap threshold are
/// accepted either way: the synchronisation may evaluate copyNeeded() in another periodic frame,
/// whose positions differ from the canonical ones by rounding (far below kOverlapMargin).
///
/// COLLECTIVE over `comm`, which must be the communicator of `local.forest()`'s ranks (any
/// duplicate of it): throws core::Error on every rank if its size differs from the forest's
/// rank count, core::BufferError on a corrupt gather (a bug).
[[nodiscard]] std::vector<std::string> checkSyncInvariants(LocalParticles const& local,
                                                           core::Comm const& comm,
                                                           bool spreadingConverged,
                                                           double skin = 0.0);

/// checkSyncInvariants(); throws core::Error on every rank (same text: `where`, then the
/// violations one per line) if any is found. COLLECTIVE over `comm`.
void requireSyncInvariants(LocalParticles const& local, core::Comm const& comm,
                           bool spreadingConverged, std::string_view where, double skin = 0.0);

/// The hook for the time step in checking builds: after each `sync.sync(local)` (and after
/// syncUntilConverged at set-up) the step loop calls
///
///     particles::checkSyncInvariantsIfEnabled(local, comm, true, "step 42");
///
/// which is requireSyncInvariants() if kCheckSyncInvariants and does nothing (no
/// communication) otherwise. Pass spreadingConverged = true once set-up converged: one sync
/// per step keeps SOS-class grains converged. COLLECTIVE over `comm` in checking builds.
inline void checkSyncInvariantsIfEnabled(LocalParticles const& local, core::Comm const& comm,
                                         bool spreadingConverged, std::string_view where) {
    if constexpr (kCheckSyncInvariants)
        requireSyncInvariants(local, comm, spreadingConverged, where);
}

} // namespace regolith::particles
