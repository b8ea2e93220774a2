#include "particles/kernels/SpringDashpot.hpp"

#include "core/Error.hpp"
#include "particles/kernels/TangentialSpring.hpp"

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
    auto const n = static_cast<std::uint32_t>(m_materials.numTypes());
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = a; b < n; ++b) {
            auto const& p = m_materials(a, b);
            auto bad = [&](char const* what, double v, char const* expected) {
                return core::InputError(
                    fmt::format("contact.{} = {} for material types ({}, {}): expected {}", what, v,
                                a, b, expected));
            };
            if (!(p.stiffness > 0.0) || !std::isfinite(p.stiffness))
                throw bad("stiffness", p.stiffness, "a positive finite value");
            if (!(p.tangentialStiffness >= 0.0) || !std::isfinite(p.tangentialStiffness))
                throw bad("tangential_stiffness", p.tangentialStiffness, "a finite value >= 0");
            if (!(p.restitution > 0.0 && p.restitution <= 1.0))
                throw bad("restitution", p.restitution, "a value in (0, 1]");
            if (!(p.friction >= 0.0) || !std::isfinite(p.friction))
                throw bad("friction", p.friction, "a finite value >= 0");
            if (!(p.tangentialDampingRatio >= 0.0) || !std::isfinite(p.tangentialDampingRatio))
                throw bad("tangential_damping_ratio", p.tangentialDampingRatio,
                          "a finite value >= 0");
            if (!(p.rollingFriction >= 0.0) || !std::isfinite(p.rollingFriction))
                throw bad("rolling_friction", p.rollingFriction, "a finite value >= 0");
            m_dampingRatio.set(a, b, dampingRatioFromRestitution(p.restitution));
        }
}

ContactResponse SpringDashpot::operator()(ContactState const& s, core::Vec3& spring,
                                          double dt) const {
    LinearContactParams const& p = m_materials(s.typeI, s.typeJ);
    double const cn =
        2.0 * m_dampingRatio(s.typeI, s.typeJ) * std::sqrt(p.stiffness * s.effectiveMass);
    double const vn = s.relativeVelocity.dot(s.normal);
    core::Vec3 const vt = s.relativeVelocity - vn * s.normal;
    double const fn = p.stiffness * s.penetration - cn * vn;

    ContactResponse r;
    r.force = fn * s.normal;
    r.force += tangentialForce(spring, s.normal, vt, p.tangentialStiffness,
                               p.tangentialDampingRatio * cn, p.friction * std::max(fn, 0.0), dt);
    r.torque = rollingTorque(s, p.rollingFriction, fn, dt);
    return r;
}

double SpringDashpot::contactTime(LinearContactParams const& p, double effectiveMass) {
    double const w0 = std::sqrt(p.stiffness / effectiveMass);
    double const gamma = dampingRatioFromRestitution(p.restitution) * w0;
    return std::numbers::pi / std::sqrt(w0 * w0 - gamma * gamma);
}

} // namespace regolith::particles
