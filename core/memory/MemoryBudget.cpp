#include "core/memory/MemoryBudget.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <limits>
#include <optional>
#include <unistd.h>

namespace regolith::core {
namespace {

std::uint64_t localPhysicalMemoryBytes() {
    long const pages = sysconf(_SC_PHYS_PAGES);
    long const size = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || size <= 0)
        return 0;
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(size);
}

/// The smallest node's memory once agreed (0: unknown on every node).
std::optional<std::uint64_t> g_agreedBytes;

} // namespace

std::uint64_t physicalMemoryBytes() {
    return g_agreedBytes ? *g_agreedBytes : localPhysicalMemoryBytes();
}

void agreeOnPhysicalMemory() {
    // Unknown (0) takes no part in the minimum.
    std::uint64_t const local = localPhysicalMemoryBytes();
    std::uint64_t mine = local == 0 ? std::numeric_limits<std::uint64_t>::max() : local;
    std::uint64_t least = mine;
    if (MPI_Allreduce(&mine, &least, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD) != MPI_SUCCESS)
        return; // keep each node's own figure
    g_agreedBytes = least == std::numeric_limits<std::uint64_t>::max() ? 0 : least;
}

void requireMemory(double bytesPerRank, std::string_view key, std::string_view what) {
    std::uint64_t const available = physicalMemoryBytes();
    if (available == 0 || !(bytesPerRank > static_cast<double>(available)))
        return;
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    throw InputError(fmt::format("{}: {} needs about {:.3g} GiB per rank, more than the {:.3g} GiB "
                                 "of this machine",
                                 key, what, bytesPerRank / kGiB,
                                 static_cast<double>(available) / kGiB));
}

} // namespace regolith::core
