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

/// Collective over MPI_COMM_WORLD, once after MPI_Init (MpiEnvironment): from then on
/// physicalMemoryBytes is the smallest of every rank's node, so that requireMemory, called with
/// values every rank agrees on, refuses on every rank or on none also when nodes differ.
void agreeOnPhysicalMemory();

/// Throws InputError "<key>: <what> needs about X GiB per rank, more than the Y GiB of this
/// machine" if `bytesPerRank` (a lower estimate; a double, so that products cannot overflow)
/// exceeds physicalMemoryBytes. Does nothing when that is unknown. Not collective: call it with
/// values every rank agrees on, or agree on the outcome.
void requireMemory(double bytesPerRank, std::string_view key, std::string_view what);

} // namespace regolith::core
