#pragma once
/// Every rank's grains on every rank, for the methods that need all sources in one place
/// (the grid baselines). O(N) memory per rank: fine for the paper's instances, not for 10⁸.
#include "core/mpi/Comm.hpp"
#include "gravity/common/PointMasses.hpp"

#include <vector>

namespace regolith::gravity {

struct OwnedMasses {
    std::vector<double> x, y, z, m, r;

    [[nodiscard]] PointMasses view() const { return {x, y, z, m, r}; }
};

/// The grains of all ranks in rank order (radii gathered if every rank has them, else
/// none). COLLECTIVE over `comm`.
[[nodiscard]] OwnedMasses gatherAll(core::Comm const& comm, PointMasses const& local);

} // namespace regolith::gravity
