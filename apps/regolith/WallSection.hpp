#pragma once
/// The scene's [[walls]] entries (docs/guide/walls.md): a shape and a rigid motion each, read
/// into particles::Wall.
#include "core/config/ConfigTable.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/storage/WallList.hpp"

#include <cstddef>

namespace regolith::apps {

/// One [[walls]] entry: shape ("plane", the default, "rectangle", "disc" or "cylinder"),
/// point, normal (plane, rectangle, disc) or axis (cylinder), size = [a, b] and edge
/// (rectangle), radius (disc, cylinder), side ("inner", the default, or "outer"; cylinder),
/// type (material index, default 0), and the motion: velocity, angular_velocity about
/// axis_point (default point), amplitude and frequency of a sinusoidal shake. Directions are
/// normalised; uid = wallUid(index). Throws core::InputError naming file, line and key (a
/// zero direction, a radius or size not positive, a key the shape does not have). Not
/// collective.
[[nodiscard]] particles::Wall parseWall(core::ConfigTable const& entry, std::size_t index);

/// Walls are not periodic: along a periodic axis of `forest` the wall `w` (parsed from
/// `entry`) must repeat itself (a plane parallel to the axis, a cylinder along it) and keep
/// doing so while it turns (a rotation about the axis), or a grain crossing the periodic face
/// would come back where the wall is not. Throws core::InputError naming the key otherwise.
/// Not collective.
void requireRepeatsAlongPeriodicAxes(core::ConfigTable const& entry, particles::Wall const& w,
                                     domain::ForestSpec const& forest);

} // namespace regolith::apps
