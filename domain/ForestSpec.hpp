#pragma once
/// What a block forest is made of: the `[domain]` section of a scene (docs/design.md, "Scene
/// file"), as plain data. Parsed from TOML by domain/ForestConfig.hpp; turned into a forest by
/// BlockForest.
#include "core/math/AABB.hpp"

#include <array>
#include <vector>

namespace regolith::domain {

/// Static refinement: every block intersecting `region` (closed) is refined until its level
/// is at least `level`; 2:1 balance then refines its neighbours as needed.
struct RefineRegion {
    core::AABB region;
    int level = 1;
};

struct ForestSpec {
    core::AABB domain{core::Vec3::Zero(), core::Vec3::Ones()};
    std::array<int, 3> rootBlocks{1, 1, 1};
    /// No `blocks` in the scene: the run chooses the root grid (one block per rank, cut
    /// with the least surface; apps resolve it before the forest is built).
    bool rootBlocksAuto = false;
    std::array<bool, 3> periodic{false, false, false};
    std::vector<RefineRegion> refine;
    /// Cells per block and axis for grid fields; zero when no grid is used.
    std::array<int, 3> cellsPerBlock{0, 0, 0};
    /// How blocks are weighed for the block -> rank assignment (domain.balance): by their
    /// load at the start (grains, and cells when a grid is used) or all alike.
    enum class Balance { Load, Blocks } balance = Balance::Load;
    /// Cost of one grid cell relative to one grain per step (domain.cell_weight), used by
    /// Balance::Load when a grid is used. Default measured, docs/results.md ("Coupled runs").
    double cellWeight = 1.0;
};

} // namespace regolith::domain
