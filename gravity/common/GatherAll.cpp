#include "gravity/common/GatherAll.hpp"

namespace regolith::gravity {

OwnedMasses gatherAll(core::Comm const& comm, PointMasses const& local) {
    bool const radii = comm.allTrue(!local.r.empty() || local.size() == 0);
    OwnedMasses all;
    auto const gather = [&](std::span<double const> mine, std::vector<double>& out) {
        out = comm.allGatherVarying(mine);
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
