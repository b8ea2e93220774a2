#pragma once
/// One participant's share of one contact, kept apart instead of summed at once, so that a
/// master's total can be summed in a canonical order (docs/design.md, "Reproducible mode").
#include "core/math/Vec3.hpp"
#include "particles/storage/Uid.hpp"

#include <cstddef>

namespace regolith::particles {

struct ForceRecord {
    std::size_t copy = 0;      ///< storage index of the copy the force acts on
    Uid partner = kInvalidUid; ///< the other particle's (or the wall's) uid
    core::Vec3 force = core::Vec3::Zero();
    core::Vec3 torque = core::Vec3::Zero();
};

} // namespace regolith::particles
