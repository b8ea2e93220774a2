#pragma once
/// What the run may read and how it replaces what it writes: inputs must be regular files
/// (a FIFO or /dev/zero would hang the reader or fill its memory), and every output goes to a
/// fresh temporary beside it and is renamed into place, so that a reader never sees a partial
/// file and an existing link or leftover temporary is never written through.
#include <functional>
#include <string>

namespace regolith::core {

/// "" if `path` names a regular file (symbolic links followed), else what it is instead:
/// "no such file", "a directory", "a FIFO", "a character device", "a block device",
/// "a socket", or the reason it cannot be examined. Not collective.
[[nodiscard]] std::string whyNotRegularFile(std::string const& path);

/// Creates a new, empty file beside `path`, named "<path>.tmp<pid>" (or with ".<n>" appended
/// while that name is taken), exclusively: never an existing file or link. Returns its name,
/// or "" and the reason in `why`. Not collective.
[[nodiscard]] std::string createTemporaryBeside(std::string const& path, std::string& why);

/// Writes the file `path` by calling `write(tmp)` on a temporary from createTemporaryBeside
/// and renaming it to `path` (the directory entry: a link named `path` is replaced, not
/// followed). Throws InputError "cannot write '<path>': <why>" if the temporary or the rename
/// fails; an exception from `write` is passed on. The temporary never stays behind.
/// Not collective.
void replaceFile(std::string const& path, std::function<void(std::string const& tmp)> const& write);

/// Writes `text` to the file `path` with replaceFile.
void replaceFileWith(std::string const& path, std::string const& text);

/// Whether `a` and `b` name the same file: the same inode where both exist (through links,
/// hard links included), else the same normalised absolute path. Not collective.
[[nodiscard]] bool sameFile(std::string const& a, std::string const& b);

} // namespace regolith::core
