#include "core/memory/MemoryBudget.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <unistd.h>

namespace regolith::core {

std::uint64_t physicalMemoryBytes() {
    long const pages = sysconf(_SC_PHYS_PAGES);
    long const size = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || size <= 0)
        return 0;
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(size);
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
