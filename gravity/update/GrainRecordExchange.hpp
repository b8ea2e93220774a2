#pragma once
/// Moving the update policy's per-grain records (UpdatePolicy.hpp) to the ranks that hold
/// the grains now: after migrations between updates, and after a restart on any layout.
#include "core/mpi/SparseExchange.hpp"
#include "gravity/update/UpdatePolicy.hpp"

#include <cstdint>
#include <span>
#include <unordered_map>

namespace regolith::gravity {

/// The directory rank of a grain: where its record is handed over (a hash of the uid, so
/// that the directories share the work whatever the uids' structure).
[[nodiscard]] int directoryRank(std::uint64_t uid, int ranks);

/// Brings the records of the grains `missing` (held here, no record here) from the ranks
/// that have them. Every rank gives away its records that the current due() call (`call`)
/// did not find a grain for (Entry::seen != call) to their directory ranks, and asks the
/// directories for the missing ones; a directory answers with the records it was given.
/// Records found are inserted with seen = call; a record nobody asked for is dropped (its
/// grain left the domain). Returns how many of `missing` got their record. COLLECTIVE over
/// the exchange's communicator (two sparse exchanges).
std::size_t fetchMigratedRecords(core::SparseExchange& exchange, int ranks,
                                 std::unordered_map<std::uint64_t, UpdatePolicy::Entry>& records,
                                 std::span<std::uint64_t const> missing, std::uint64_t call);

} // namespace regolith::gravity
