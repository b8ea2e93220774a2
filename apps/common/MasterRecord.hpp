#pragma once
/// One master particle as the apps report it (checksum, `--dump`, conserved quantities): plain
/// data, independent of the particle storage, in the columns of the dump contract
/// (DESIGN.md, "Run summary": uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass).
#include "core/math/Vec3.hpp"

#include <cstdint>

namespace regolith::apps {

struct MasterRecord {
    std::uint64_t uid = 0;                           ///< globally unique particle id
    core::Vec3 position = core::Vec3::Zero();        ///< centre [length]
    core::Vec3 velocity = core::Vec3::Zero();        ///< [length/time]
    core::Vec3 angularVelocity = core::Vec3::Zero(); ///< [rad/time]
    double radius = 0.0;                             ///< [length]
    double mass = 0.0;                               ///< [mass]
};

} // namespace regolith::apps
