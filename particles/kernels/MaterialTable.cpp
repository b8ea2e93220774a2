#include "particles/kernels/MaterialTable.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace regolith::particles {

void throwBadMaterialType(std::uint32_t type, std::size_t numTypes) {
    throw core::InputError("material type " + std::to_string(type) + " is not below the " +
                           std::to_string(numTypes) + " declared types");
}

namespace {
[[noreturn]] void throwBadMaterial(MaterialCheck const& c, char const* key, double value,
                                   char const* expected) {
    throw core::InputError(fmt::format("contact.{} = {} for material types ({}, {}): expected {}",
                                       key, value, c.a, c.b, expected));
}
} // namespace

void MaterialCheck::positive(char const* key, double value) const {
    if (!(value > 0.0) || !std::isfinite(value))
        throwBadMaterial(*this, key, value, "a positive finite value");
}

void MaterialCheck::nonNegative(char const* key, double value) const {
    if (!(value >= 0.0) || !std::isfinite(value))
        throwBadMaterial(*this, key, value, "a finite value >= 0");
}

void MaterialCheck::restitution(double value) const {
    if (!(value > 0.0 && value <= 1.0))
        throwBadMaterial(*this, "restitution", value, "a value in (0, 1]");
}

void MaterialCheck::rollingSpring(double stiffness, double dampingRatio,
                                  double normalStiffness) const {
    nonNegative("rolling_stiffness", stiffness);
    nonNegative("rolling_damping_ratio", dampingRatio);
    if (normalStiffness > 0.0 && stiffness > normalStiffness)
        throw core::InputError(fmt::format(
            "contact.rolling_stiffness = {} for material types ({}, {}): expected at most the "
            "normal stiffness {} (a stiffer rolling spring oscillates faster than the normal "
            "contact, whose duration sets the time step)",
            stiffness, a, b, normalStiffness));
}

} // namespace regolith::particles
