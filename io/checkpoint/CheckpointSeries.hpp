#pragma once
/// The checkpoints of a run in its output directory: their names and their rotation.
#include <cstdint>
#include <string>
#include <vector>

namespace regolith::io {

/// "<dir>/checkpoint_<step>.h5" with the step zero-padded to 8 digits, so that names sort
/// by step. Not collective.
[[nodiscard]] std::string checkpointPath(std::string const& dir, std::int64_t step);

/// The checkpoints in `dir` that a run writing every `every` steps after `firstStep` up to
/// `lastStep` would replace (an earlier run's of the same steps), by name. Not collective.
[[nodiscard]] std::vector<std::string> checkpointsToReplace(std::string const& dir,
                                                            std::int64_t every,
                                                            std::int64_t firstStep,
                                                            std::int64_t lastStep);

/// Why `path` cannot be a checkpoint this library wrote ("" if it may be one): it is not a
/// regular file, or its first bytes are not HDF5's signature (the writer uses no user block).
/// For a run about to replace it. Not collective.
[[nodiscard]] std::string notACheckpointFile(std::string const& path);

/// Deletes the checkpoints of `written` (the ones this run wrote, oldest first) except the
/// newest `keep` (keep <= 0: deletes none), drops them from the list and returns them. Files
/// this run did not write -- an earlier run's in the same directory, the checkpoint it
/// restarted from -- are never touched, so a run cannot rotate its own new checkpoints away
/// behind higher-numbered old ones. Call on one rank. Not collective.
std::vector<std::string> rotateCheckpoints(std::vector<std::string>& written, std::int64_t keep);

} // namespace regolith::io
