#pragma once
/// Internal to io/: the walls as polygons for ParaView (VtkOutput's walls series). Infinite
/// walls are cut to the domain box: a plane to its section with the box, a cylinder to the
/// box's extent along its axis.
#include "core/math/AABB.hpp"
#include "particles/storage/WallList.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace regolith::io::detail {

/// Polygons with point data `velocity` (the wall material's velocity there) and cell data
/// `wall` (index in [[walls]] order) and `type` (material).
struct WallMesh {
    std::vector<double> xyz;           ///< 3 per point
    std::vector<double> velocity;      ///< 3 per point
    std::vector<std::int64_t> offsets; ///< polygon k: connectivity[offsets[k], offsets[k+1])
    std::vector<std::int64_t> connectivity;
    std::vector<std::int32_t> wall; ///< per polygon
    std::vector<std::int32_t> type; ///< per polygon
};

/// Sides of the polygon that stands for a disc or a cylinder's circle.
inline constexpr int kCircleSides = 48;

/// The walls as they stand now (WallList::moveTo), cut to `domain`. A plane that misses the
/// box has no polygon. Not collective.
[[nodiscard]] WallMesh wallMesh(particles::WallList const& walls, core::AABB const& domain);

/// Writes `mesh` as VTK XML polydata (.vtp). Throws core::Error naming `path` if VTK fails.
/// Not collective.
void writeWallPiece(std::string const& path, WallMesh const& mesh);

} // namespace regolith::io::detail
