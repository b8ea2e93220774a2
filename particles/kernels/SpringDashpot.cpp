#include "particles/kernels/SpringDashpot.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace regolith::particles {

double dampingRatioFromRestitution(double e) {
    double const l = std::log(e);
    return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

SpringDashpot::SpringDashpot(MaterialTable<LinearContactParams> materials)
    : m_materials(std::move(materials))
    , m_dampingRatio(m_materials.numTypes(), 0.0) {
    m_materials.forEachPair([this](std::uint32_t a, std::uint32_t b, LinearContactParams const& p) {
        MaterialCheck const check{a, b};
        check.positive("stiffness", p.stiffness);
        check.nonNegative("tangential_stiffness", p.tangentialStiffness);
        check.restitution(p.restitution);
        check.nonNegative("friction", p.friction);
        check.nonNegative("tangential_damping_ratio", p.tangentialDampingRatio);
        check.nonNegative("rolling_friction", p.rollingFriction);
        check.rollingSpring(p.rollingSpring.stiffness, p.rollingSpring.dampingRatio, p.stiffness);
        m_rollingSpring = m_rollingSpring || p.rollingSpring.enabled;
        m_dampingRatio.set(a, b, dampingRatioFromRestitution(p.restitution));
    });
}

double SpringDashpot::contactTime(LinearContactParams const& p, double effectiveMass) {
    double const w0 = std::sqrt(p.stiffness / effectiveMass);
    double const gamma = dampingRatioFromRestitution(p.restitution) * w0;
    return std::numbers::pi / std::sqrt(w0 * w0 - gamma * gamma);
}

double SpringDashpot::undampedContactTime(LinearContactParams const& p, double effectiveMass) {
    return std::numbers::pi * std::sqrt(effectiveMass / p.stiffness);
}

} // namespace regolith::particles
