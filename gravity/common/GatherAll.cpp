#include "gravity/common/GatherAll.hpp"

#include <mpi.h>

namespace regolith::gravity {

OwnedMasses gatherAll(core::Comm const& comm, PointMasses const& local) {
    std::vector<int> const counts = comm.allGather(static_cast<int>(local.size()));
    std::vector<int> displs(counts.size(), 0);
    int total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
        displs[r] = total;
        total += counts[r];
    }
    bool const radii = comm.allTrue(!local.r.empty() || local.size() == 0);
    OwnedMasses all;
    auto const gather = [&](std::span<double const> mine, std::vector<double>& out) {
        out.resize(static_cast<std::size_t>(total));
        core::Comm::check(MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE,
                                         out.data(), counts.data(), displs.data(), MPI_DOUBLE,
                                         comm.raw()),
                          "MPI_Allgatherv (gather grains)");
    };
    gather(local.x, all.x);
    gather(local.y, all.y);
    gather(local.z, all.z);
    gather(local.m, all.m);
    if (radii) {
        std::vector<double> const none;
        gather(local.r.empty() ? std::span<double const>(none) : local.r, all.r);
    }
    return all;
}

} // namespace regolith::gravity
