#pragma once
/// Predicates for ConfigTable::getIf / getOrIf, with the phrases they pair with.
#include "core/math/Vec3.hpp"

#include <cmath>
#include <cstdint>

namespace regolith::core {

/// "a positive finite number"
inline bool isPositiveFinite(double x) {
    return std::isfinite(x) && x > 0.0;
}
/// "a non-negative finite number"
inline bool isNonNegativeFinite(double x) {
    return std::isfinite(x) && x >= 0.0;
}
/// "a non-negative integer"
inline bool isNonNegative(std::int64_t n) {
    return n >= 0;
}
/// "an array of 3 finite numbers"
inline bool isFiniteVec3(Vec3 const& v) {
    return v.allFinite();
}

} // namespace regolith::core
