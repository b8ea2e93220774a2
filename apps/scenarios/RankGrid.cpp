#include "apps/scenarios/RankGrid.hpp"

#include "core/Error.hpp"

namespace regolith::apps {

std::array<int, 3> rankGrid(int ranks, int axes) {
    if (ranks < 1 || (axes != 2 && axes != 3))
        throw core::Error("rankGrid: ranks >= 1 and 2 or 3 axes expected");
    std::array<int, 3> best{ranks, 1, 1};
    // Exhaustive over divisors: ranks is at most a few thousand here.
    for (int z = 1; z <= (axes == 3 ? ranks : 1); ++z) {
        if (ranks % z != 0)
            continue;
        for (int y = z; y <= ranks / z; ++y) {
            if ((ranks / z) % y != 0)
                continue;
            int const x = ranks / z / y;
            if (x < y)
                break;
            if (x - z < best[0] - best[2])
                best = {x, y, z};
        }
    }
    return best;
}

} // namespace regolith::apps
