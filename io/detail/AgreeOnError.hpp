#pragma once
/// Internal to io/: one input error for every rank when some ranks fail alone (a file read
/// by every rank by itself). apps/ has its own (AgreeOnInputError); io/ may not include apps/.
#include "core/mpi/Comm.hpp"

#include <functional>

namespace regolith::io::detail {

/// Runs `action`; if it throws core::InputError on any rank, every rank throws
/// core::InputError with the message of the lowest failing rank. `action` must not call
/// collectives. COLLECTIVE over `comm` (two small collectives on failure, one otherwise).
void agreeOnError(core::Comm const& comm, std::function<void()> const& action);

} // namespace regolith::io::detail
