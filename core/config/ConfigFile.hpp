#pragma once
/// Reading configuration files: locally, or once on rank 0 for everybody.
#include "core/config/ConfigTable.hpp"
#include "core/mpi/Comm.hpp"

#include <string>

namespace regolith::core {

/// The whole content of the file at `path`. Throws InputError "cannot read '<path>': <why>"
/// when it does not exist, is a directory or cannot be read. Not collective.
[[nodiscard]] std::string readTextFile(std::string const& path);

/// Reads the file at `path` on rank 0 of `comm`, broadcasts its text (or the reason it could
/// not be read) and parses it on every rank, so that a job on thousands of ranks opens the
/// file once and every rank sees the same text. Throws the same InputError on every rank.
/// COLLECTIVE over `comm`.
[[nodiscard]] ConfigTable loadConfigFile(Comm const& comm, std::string const& path);

} // namespace regolith::core
