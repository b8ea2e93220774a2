#pragma once
/// A double stored as a float on the safe side of a bound: the nearest float may lie on the
/// wrong one (a gap that must not grow, a reach that must not shrink).
#include <cmath>
#include <limits>

namespace regolith::core {

/// The smallest float not below x (NaN stays NaN).
[[nodiscard]] inline float floatNotBelow(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) >= x ? f
                                       : std::nextafter(f, std::numeric_limits<float>::infinity());
}

/// The largest float not above x (NaN stays NaN).
[[nodiscard]] inline float floatNotAbove(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) <= x ? f
                                       : std::nextafter(f, -std::numeric_limits<float>::infinity());
}

} // namespace regolith::core
