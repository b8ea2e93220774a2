#pragma once
/// The set-up check that no uid is a master twice anywhere: a grain inserted twice with the
/// same uid (two generators, a restart file listing a grain twice) would otherwise be
/// synchronised as two particles whose shadows overwrite each other.
#include "core/mpi/Comm.hpp"
#include "particles/sync/BlockParticles.hpp"

namespace regolith::particles {

/// Throws core::InputError on every rank, with the same text, if some uid is a master in two
/// places (two blocks, on one rank or on two): it names the smallest such uid, the two
/// positions, blocks and ranks, and how many uids are duplicated in total. Returns normally
/// on every rank otherwise.
///
/// Algorithm: every master's (uid, position, block) is routed to rank uid mod P with one
/// sparse exchange (core::SparseExchange, NBX), which sorts what it receives and finds
/// neighbours with equal uids; one all-reduce agrees on the smallest duplicate and one
/// broadcast from its checking rank carries the message. O(N/P) memory and work per rank for
/// N masters spread evenly, O(log P) collectives.
///
/// COLLECTIVE over `comm` (the communicator of `local.forest()`'s ranks).
void verifyUniqueMasters(LocalParticles const& local, core::Comm const& comm);

} // namespace regolith::particles
