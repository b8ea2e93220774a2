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
/// The most ranks on one node once agreed.
int g_ranksPerNode = 1;

/// The ranks of MPI_COMM_WORLD on this rank's node, or 1 if MPI cannot tell.
int localRanksOnNode() {
    MPI_Comm node = MPI_COMM_NULL;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) !=
            MPI_SUCCESS ||
        node == MPI_COMM_NULL)
        return 1;
    int size = 1;
    MPI_Comm_size(node, &size);
    MPI_Comm_free(&node);
    return size;
}

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
    int const onNode = localRanksOnNode();
    int most = onNode;
    if (MPI_Allreduce(&onNode, &most, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS)
        g_ranksPerNode = most;
}

int ranksPerNode() {
    return g_ranksPerNode;
}

void requireMemory(double bytesPerRank, std::string_view key, std::string_view what) {
    std::uint64_t const available = physicalMemoryBytes();
    int const ranks = ranksPerNode();
    double const node = bytesPerRank * ranks;
    if (available == 0 || !(node > static_cast<double>(available)))
        return;
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    double const have = static_cast<double>(available) / kGiB;
    if (ranks == 1)
        throw InputError(fmt::format("{}: {} needs about {:.3g} GiB per rank, more than the {:.3g} "
                                     "GiB of this machine; change {}",
                                     key, what, bytesPerRank / kGiB, have, key));
    throw InputError(fmt::format("{}: {} needs about {:.3g} GiB per rank, {:.3g} GiB for the {} "
                                 "ranks on a node, more than the {:.3g} GiB of the node; change "
                                 "{}, or run fewer ranks per node",
                                 key, what, bytesPerRank / kGiB, node / kGiB, ranks, have, key));
}

} // namespace regolith::core
