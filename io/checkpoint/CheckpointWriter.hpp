#pragma once
/// Writing a checkpoint: one HDF5 file for the whole job, written collectively by all ranks
/// with parallel HDF5 (MPI-IO), never left half-written under its final name.
#include "core/mpi/Comm.hpp"
#include "io/checkpoint/CheckpointInfo.hpp"
#include "io/checkpoint/GrainState.hpp"

#include <span>
#include <string>

namespace regolith::io {

/// Writes `grains` (this rank's masters; any count, also none) and `info` to `path`, in the
/// layout of CheckpointInfo.hpp: first to a fresh temporary "<path>.tmp<pid>" that rank 0
/// creates (core::createTemporaryBeside: a leftover one, or a link, is never written
/// through), which is flushed, closed and synced
/// to disk, then, after a barrier, renamed to `path` by rank 0 (an atomic replacement on a
/// POSIX file system). A crash at any moment therefore leaves either the previous file at
/// `path` or the complete new one. Fills info.grainCount, historyCount and returns the file
/// size in bytes.
///
/// Test hook: if the environment variable REGOLITH_TEST_ABORT_IN_CHECKPOINT holds
/// `info.step`, every rank ends the process (std::_Exit(86), no clean-up) after half the
/// datasets were written and flushed: a writer killed mid-write.
///
/// Errors: the temporary file cannot be created (directory missing or not writable) →
/// core::InputError "cannot write checkpoint '<path>': ..." on every rank; a failure later
/// (disk full, I/O error) → core::Error (the job is aborted). COLLECTIVE over `comm`.
std::uint64_t writeCheckpoint(core::Comm const& comm, std::string const& path, CheckpointInfo& info,
                              std::span<GrainState const> grains);

} // namespace regolith::io
