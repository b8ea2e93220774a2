#pragma once
/// A double stored as a float on the safe side of a bound: the nearest float may lie on the
/// wrong one (a gap that must not grow, a reach that must not shrink).
///
/// The step to the neighbouring float is taken on the bits (one integer add), not through
/// libm's nextafter: a list rebuild stores a gap per listed pair, and half of them need the
/// step (a call each, ~1 % of a dense pack's run).
#include <bit>
#include <cstdint>
#include <limits>

namespace regolith::core {

namespace float_bounds_detail {
/// The float next to f towards +infinity (up) or -infinity (!up); f neither NaN nor the
/// infinity in that direction.
[[nodiscard]] inline float step(float f, bool up) {
    if (f == 0.0F) // +0 and -0 alike: the smallest subnormal of the direction's sign
        return up ? std::numeric_limits<float>::denorm_min()
                  : -std::numeric_limits<float>::denorm_min();
    // Sign and magnitude: the magnitude's bits grow away from zero.
    bool const away = (f > 0.0F) == up;
    auto const bits = std::bit_cast<std::uint32_t>(f);
    return std::bit_cast<float>(away ? bits + 1U : bits - 1U);
}
} // namespace float_bounds_detail

/// The smallest float not below x (NaN stays NaN).
[[nodiscard]] inline float floatNotBelow(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) >= x || x != x ? f : float_bounds_detail::step(f, true);
}

/// The largest float not above x (NaN stays NaN).
[[nodiscard]] inline float floatNotAbove(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) <= x || x != x ? f : float_bounds_detail::step(f, false);
}

} // namespace regolith::core
