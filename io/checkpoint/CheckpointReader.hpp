#pragma once
/// Reading a checkpoint written by writeCheckpoint, on any number of ranks.
#include "core/mpi/Comm.hpp"
#include "io/checkpoint/CheckpointInfo.hpp"
#include "io/checkpoint/GrainState.hpp"

#include <string>
#include <vector>

namespace regolith::io {

/// What one rank read: the file's header and its slice of the grains.
struct CheckpointSlice {
    CheckpointInfo info;
    std::vector<GrainState> grains; ///< rows [N r / P, N (r+1) / P) of the file
};

/// Reads `path`: every rank opens the file read-only by itself (no MPI-IO: a damaged file
/// then cannot leave ranks waiting in a collective HDF5 call), reads the attributes and its
/// slice of the grains with their contact history, and the ranks verify the file checksum
/// together. The grains are where the file has them, not yet where the forest wants them
/// (see restoreGrains).
///
/// Errors, thrown on every rank as the same core::InputError "checkpoint '<path>': <what>":
/// the file does not exist, is not an HDF5 file, is truncated or damaged (HDF5 cannot open
/// it, a dataset or attribute is missing or has the wrong size), has another format version
/// ("format version 7, this build reads version 1"), or its checksum does not match the
/// data. The file is only read. COLLECTIVE over `comm`.
[[nodiscard]] CheckpointSlice readCheckpoint(core::Comm const& comm, std::string const& path);

} // namespace regolith::io
