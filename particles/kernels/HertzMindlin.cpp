#include "particles/kernels/HertzMindlin.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regolith::particles {

HertzMindlinParams HertzMindlinParams::fromMaterials(double youngsA, double poissonA,
                                                     double youngsB, double poissonB,
                                                     double restitution, double friction,
                                                     double rollingFriction) {
    for (auto [e, nu] : {std::pair(youngsA, poissonA), std::pair(youngsB, poissonB)}) {
        if (!(e > 0.0) || !std::isfinite(e))
            throw core::InputError(
                fmt::format("contact.youngs_modulus = {}: expected a positive finite value", e));
        if (!(nu > -1.0 && nu <= 0.5))
            throw core::InputError(
                fmt::format("contact.poisson_ratio = {}: expected a value in (-1, 0.5]", nu));
    }
    HertzMindlinParams p;
    p.effectiveYoungsModulus =
        1.0 / ((1.0 - poissonA * poissonA) / youngsA + (1.0 - poissonB * poissonB) / youngsB);
    p.effectiveShearModulus = 1.0 / (2.0 * (2.0 - poissonA) * (1.0 + poissonA) / youngsA +
                                     2.0 * (2.0 - poissonB) * (1.0 + poissonB) / youngsB);
    p.restitution = restitution;
    p.friction = friction;
    p.rollingFriction = rollingFriction;
    return p;
}

HertzMindlin::HertzMindlin(MaterialTable<HertzMindlinParams> materials)
    : m_materials(std::move(materials))
    , m_beta(m_materials.numTypes(), 0.0) {
    m_materials.forEachPair([this](std::uint32_t a, std::uint32_t b, HertzMindlinParams const& p) {
        MaterialCheck const check{a, b};
        check.positive("youngs_modulus (effective)", p.effectiveYoungsModulus);
        check.nonNegative("shear_modulus (effective)", p.effectiveShearModulus);
        check.restitution(p.restitution);
        check.nonNegative("friction", p.friction);
        check.nonNegative("rolling_friction", p.rollingFriction);
        check.rollingSpring(p.rollingSpring.stiffness, p.rollingSpring.dampingRatio, 0.0);
        m_rollingSpring = m_rollingSpring || p.rollingSpring.enabled;
        double const l = std::log(p.restitution);
        double const beta = l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
        m_beta.set(a, b, -2.0 * std::sqrt(5.0 / 6.0) * beta);
    });
}

double HertzMindlin::contactTime(HertzMindlinParams const& p, double effectiveMass,
                                 double effectiveRadius, double impactVelocity) {
    double const e = p.effectiveYoungsModulus;
    return 2.868 *
           std::pow(effectiveMass * effectiveMass / (effectiveRadius * e * e * impactVelocity),
                    0.2);
}

} // namespace regolith::particles
