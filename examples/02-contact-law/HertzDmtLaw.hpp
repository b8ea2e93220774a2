#pragma once
// Tutorial 02's contact law, whole: its kernel, its scene keys and their checks, its contact
// time for the dt guard and its registry entry. Registering the entry (one line, main.cpp)
// makes it a contact.model a scene or a program may name.
//
// The law (Derjaguin, Muller & Toporov 1975): a Hertz spring with a constant adhesive pull
// while the grains touch, F_n = 4/3 E* sqrt(R*) delta^(3/2) - 2 pi w R* - c v_n, with w the
// work of adhesion [energy / area] and a dashpot c = 2 zeta sqrt(m* k) on the tangent
// stiffness k = 2 E* sqrt(R* delta).
#include "core/config/ConfigTable.hpp"
#include "core/config/ValueChecks.hpp"
#include "core/math/Vec3.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

#include <cmath>
#include <numbers>

namespace tutorial {

using regolith::core::Vec3;
namespace particles = regolith::particles;

struct HertzDmtLaw {
    double modulus = 0.0; ///< E* [pressure]
    double work = 0.0;    ///< w [energy / area]
    double damping = 0.0; ///< zeta

    /// The kernel: every contact, one direct call. `s.penetration` > 0 is the overlap,
    /// `s.normal` points from i to j, the force returned acts on j (i gets the opposite).
    particles::ContactResponse operator()(particles::ContactState const& s, Vec3& /*spring*/,
                                          Vec3& /*rolling*/, double /*dt*/) const {
        double const r = s.effectiveRadius;
        double const elastic = 4.0 / 3.0 * modulus * std::sqrt(r) * std::pow(s.penetration, 1.5);
        double const k = 2.0 * modulus * std::sqrt(r * s.penetration);
        double const vn = s.relativeVelocity.dot(s.normal);
        double const fn =
            elastic - pullOff(r) - 2.0 * damping * std::sqrt(k * s.effectiveMass) * vn;
        return {fn * s.normal, Vec3::Zero()}; // frictionless: no tangential force, no couple
    }
    [[nodiscard]] bool hasRollingSpring() const { return false; }

    [[nodiscard]] double pullOff(double effectiveRadius) const {
        return 2.0 * std::numbers::pi * work * effectiveRadius;
    }
    /// The overlap at which the Hertz force balances the adhesion.
    [[nodiscard]] double restingOverlap(double effectiveRadius) const {
        return std::pow(pullOff(effectiveRadius) /
                            (4.0 / 3.0 * modulus * std::sqrt(effectiveRadius)),
                        2.0 / 3.0);
    }

    /// Its scene keys in [contact], each checked (the message names the key).
    static HertzDmtLaw fromScene(regolith::core::ConfigTable const& t) {
        using regolith::core::isPositiveFinite;
        return {t.getIf<double>("effective_modulus", isPositiveFinite, "a positive modulus"),
                t.getIf<double>("adhesion_work", isPositiveFinite, "a positive work of adhesion"),
                t.getIf<double>("damping_ratio", isPositiveFinite, "a positive damping ratio")};
    }
};

/// The dt guard's time scale, found by the step through argument-dependent lookup: the period
/// of small oscillations about the resting overlap of two like grains of the lightest one.
inline particles::ContactTimeEstimate estimateContactTime(particles::ParticleStorage const& ps,
                                                          HertzDmtLaw const& law) {
    particles::ContactTimeEstimate e;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        double const m = 0.5 * ps.mass(i), r = 0.5 * ps.radius(i);
        double const k = 2.0 * law.modulus * std::sqrt(r * law.restingOverlap(r));
        double const t = std::numbers::pi * std::sqrt(m / k);
        if (t < e.contactTime)
            e = {t, "contact.effective_modulus", law.modulus, ps.mass(i), ps.uid(i)};
    }
    return e;
}

/// The registry entry: contact.model = "hertz-dmt".
inline particles::ContactModelEntry hertzDmtEntry() {
    return {"hertz-dmt", particles::Elasticity::Linear,
            [](regolith::core::ConfigTable const& t) { (void)HertzDmtLaw::fromScene(t); },
            [](particles::ContactModelInputs const& in) {
                return particles::AnyContactModel(HertzDmtLaw::fromScene(in.contact));
            }};
}

} // namespace tutorial
