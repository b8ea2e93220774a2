#pragma once
// Forests for the grid-gravity tests: `blocksPerRank` blocks on each rank of the world, laid
// out as a power-of-two grid of root blocks over a cube, with a given number of cells in
// total per axis.
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"

#include <array>
#include <string>

namespace regolith::gravity::test {

/// Root blocks per axis for `total` blocks (a power of two), most on x.
inline std::array<int, 3> blockGrid(int total) {
    std::array<int, 3> g{1, 1, 1};
    for (int a = 0; total > 1; a = (a + 1) % 3, total /= 2)
        g[a] *= 2;
    return g;
}

inline domain::ForestSpec cubeSpec(core::Comm const& comm, int blocksPerRank, int cellsPerAxis,
                                   std::array<bool, 3> periodic, double halfWidth = 1.0) {
    domain::ForestSpec s;
    s.domain = core::AABB{core::Vec3::Constant(-halfWidth), core::Vec3::Constant(halfWidth)};
    s.rootBlocks = blockGrid(comm.size() * blocksPerRank);
    s.periodic = periodic;
    for (int a = 0; a < 3; ++a)
        s.cellsPerBlock[a] = cellsPerAxis / s.rootBlocks[a];
    return s;
}

inline std::string describe(domain::ForestSpec const& s) {
    return "blocks " + std::to_string(s.rootBlocks[0]) + "x" + std::to_string(s.rootBlocks[1]) +
           "x" + std::to_string(s.rootBlocks[2]) + " periodic " + std::to_string(s.periodic[0]) +
           std::to_string(s.periodic[1]) + std::to_string(s.periodic[2]) + " cells/block " +
           std::to_string(s.cellsPerBlock[0]);
}

} // namespace regolith::gravity::test
