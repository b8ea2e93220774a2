#pragma once
/// Keeps a second run out of an output folder while a first one writes there. Two runs writing
/// the same summary, VTK series and checkpoints would replace each other's files mid-run.
#include "core/mpi/Comm.hpp"

#include <string>

namespace regolith::apps {

/// Rank 0 holds an exclusive lock on the folder itself (flock of the open directory) while the
/// object lives: no file is added to the folder, and the lock goes with the process, so a
/// killed run leaves nothing behind. A run started on the folder while another holds it stops
/// before its first step. Where the file system keeps no locks (some network mounts) the run
/// goes on after a warning. Move-only.
class OutputDirLock {
public:
    OutputDirLock() = default;
    /// Creates `dir` if missing and takes its lock (none if the folder cannot be made: the
    /// outputs' own checks then refuse the run). COLLECTIVE over `comm`; throws
    /// core::InputError on every rank ("output.dir = \"<dir>\": another run is writing
    /// there ...") if another process holds it.
    OutputDirLock(core::Comm const& comm, std::string const& dir);
    OutputDirLock(OutputDirLock&& other) noexcept;
    OutputDirLock& operator=(OutputDirLock&& other) noexcept;
    OutputDirLock(OutputDirLock const&) = delete;
    OutputDirLock& operator=(OutputDirLock const&) = delete;
    ~OutputDirLock();

private:
    int m_fd = -1; ///< the folder, open on rank 0 while the lock is held
};

} // namespace regolith::apps
