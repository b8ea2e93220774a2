#pragma once
/// How much memory this machine has, and a check that a planned allocation fits in it, so that
/// an input asking for more (a grid of 2048^3 cells per block, 10^12 grains) is an input error
/// naming the key instead of std::bad_alloc, or the machine swapping, deep inside the set-up.
#include <cstdint>
#include <string_view>

namespace regolith::core {

/// Physical memory of this node [bytes] (sysconf), or 0 if unknown.
[[nodiscard]] std::uint64_t physicalMemoryBytes();

/// Throws InputError "<key>: <what> needs about X GiB per rank, more than the Y GiB of this
/// machine" if `bytesPerRank` (a lower estimate; a double, so that products cannot overflow)
/// exceeds the node's physical memory. Does nothing when that is unknown. Local: call it with
/// values every rank agrees on, or agree on the outcome.
void requireMemory(double bytesPerRank, std::string_view key, std::string_view what);

} // namespace regolith::core
