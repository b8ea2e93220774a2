#include "particles/generators/GrainInit.hpp"

#include <numbers>

namespace regolith::particles {

double sphereMass(double radius, double density) {
    return (4.0 / 3.0) * std::numbers::pi * (radius * radius * radius) * density;
}

} // namespace regolith::particles
