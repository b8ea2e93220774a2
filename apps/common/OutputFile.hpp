#pragma once
/// Output files written by one rank for the whole job (run summary, final dump), without
/// half-written files and with one error for everybody when the file cannot be written.
#include "core/mpi/Comm.hpp"

#include <string>
#include <string_view>

namespace regolith::apps {

/// Whether `path` exists and is written in place rather than replaced: neither a regular file
/// nor a directory (through symlinks: a FIFO, a device such as /dev/null, a socket), or
/// anything under /dev or /proc (/dev/stdout redirected to a file included). Not collective.
[[nodiscard]] bool writtenInPlace(std::string const& path);

/// Writes `text` to a fresh temporary in the same directory (core::replaceFile), then renames
/// it to `path`, so a reader never sees a partial file. Through a symbolic link, the file it names
/// is replaced (the link stays); a FIFO, a device or anything under /dev or /proc (/dev/null,
/// /dev/stdout, also when that is redirected to a file) is written in place, never replaced. Throws
/// core::InputError "cannot write '<path>': <why>". Not collective.
void writeFileAtomically(std::string const& path, std::string_view text);

/// Rank 0 writes `text` (ignored on other ranks) with writeFileAtomically; every rank learns
/// the outcome and throws the same core::InputError if it failed. COLLECTIVE over `comm`.
void writeFileOnRoot(core::Comm const& comm, std::string const& path, std::string_view text);

/// Checks before the run that `path` could be written: it names a file (not "dir/"), its
/// directory exists (created if missing) and is writable.
/// Rank 0 checks; every rank throws the same core::InputError "<option> <path>: ..." if not,
/// so a long run never ends with an unwritable summary. COLLECTIVE over `comm`.
void checkWritable(core::Comm const& comm, std::string const& path, std::string_view option);

} // namespace regolith::apps
