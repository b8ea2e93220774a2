#pragma once
/// How much memory this machine has, and a check that a planned allocation fits in it, so that
/// an input asking for more (a grid of 2048^3 cells per block, 10^12 grains) is an input error
/// naming the key instead of std::bad_alloc, or the machine swapping, deep inside the set-up.
#include <cstdint>
#include <string_view>

namespace regolith::core {

/// Physical memory of this node [bytes] (sysconf), or 0 if unknown; after
/// agreeOnPhysicalMemory, the smallest node's.
[[nodiscard]] std::uint64_t physicalMemoryBytes();

/// How many ranks share a node: 1 until agreeOnPhysicalMemory, then the most on any node
/// (MPI_COMM_TYPE_SHARED).
[[nodiscard]] int ranksPerNode();

/// Collective over MPI_COMM_WORLD, once after MPI_Init (MpiEnvironment): from then on
/// physicalMemoryBytes is the smallest of every rank's node and ranksPerNode the largest
/// count of ranks on one, so that requireMemory, called with values every rank agrees on,
/// refuses on every rank or on none also when nodes differ.
void agreeOnPhysicalMemory();

/// Throws InputError "<key>: <what> needs about X GiB per rank, Y GiB for the N ranks on a
/// node, more than the Z GiB of the node; change <key> ..." if `bytesPerRank` (a lower
/// estimate; a double, so that products cannot overflow) times ranksPerNode exceeds
/// physicalMemoryBytes: every rank of a node needs its share at once. Does nothing when that
/// is unknown. Not collective: call it with values every rank agrees on, or agree on the
/// outcome.
void requireMemory(double bytesPerRank, std::string_view key, std::string_view what);

} // namespace regolith::core
