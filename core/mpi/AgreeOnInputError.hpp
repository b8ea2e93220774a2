#pragma once
/// Turns an input error that only some ranks see into one that every rank sees.
#include "core/mpi/Comm.hpp"

#include <functional>

namespace regolith::core {

/// Runs `action` on this rank. If it throws core::InputError on any rank — also on some ranks
/// only, e.g. a file readable on some nodes, or a check of rank-local data — every rank
/// throws core::InputError with the message of the lowest-numbered failing rank (broadcast
/// from there), so the entry point (core::runApp) prints one message and every rank exits
/// cleanly instead of some ranks waiting in the next collective. An empty message is
/// replaced by "unknown input error". Any other exception leaves `action` on its rank
/// unchanged (a one-rank failure: the entry point aborts the job).
///
/// Cost on success: one MPI_Allreduce of an int. COLLECTIVE over `comm`: every rank must call
/// it, and `action` must not call collectives that other ranks could skip by failing early.
void agreeOnInputError(core::Comm const& comm, std::function<void()> const& action);

} // namespace regolith::core
