#pragma once
/// The checkpoints of a run in its output directory: their names and their rotation.
#include <cstdint>
#include <string>
#include <vector>

namespace regolith::io {

/// "<dir>/checkpoint_<step>.h5" with the step zero-padded to 8 digits, so that names sort
/// by step. Not collective.
[[nodiscard]] std::string checkpointPath(std::string const& dir, std::int64_t step);

/// Deletes every file of `dir` named like checkpointPath except the `keep` with the highest
/// steps (keep <= 0: deletes none); returns the deleted paths. Files that are not
/// checkpoints, and temporary files, are left alone. Call on one rank. Not collective.
std::vector<std::string> rotateCheckpoints(std::string const& dir, std::int64_t keep);

} // namespace regolith::io
