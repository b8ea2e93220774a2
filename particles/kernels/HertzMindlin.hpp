#pragma once
/// Hertz–Mindlin contact model: Hertz normal force, Mindlin tangential stiffness with a
/// history spring and Coulomb limit, restitution-based damping of Tsuji, Tanaka & Ishida
/// (Powder Technol. 71 (1992) 239) in the form of Antypov & Elliott (EPL 94 (2011) 50004) and
/// LIGGGHTS' hertz/history; optional rolling resistance.
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/MaterialTable.hpp"
#include "particles/kernels/TangentialSpring.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

/// Parameters of one pair of materials, in effective (pair) form.
struct HertzMindlinParams {
    double effectiveYoungsModulus = 0.0; ///< E* [pressure], > 0
    double effectiveShearModulus = 0.0;  ///< G* [pressure], >= 0
    double restitution = 1.0;            ///< e in (0, 1]
    double friction = 0.0;               ///< Coulomb mu >= 0
    double rollingFriction = 0.0;        ///< mu_r >= 0, dimensionless
    RollingSpring rollingSpring; ///< model C if enabled, else model A (TangentialSpring.hpp)

    /// The pair of two materials with Young's moduli E and Poisson ratios nu:
    /// 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b,
    /// 1/G* = 2 (2 - nu_a)(1 + nu_a)/E_a + 2 (2 - nu_b)(1 + nu_b)/E_b (Di Renzo & Di Maio,
    /// Chem. Eng. Sci. 59 (2004) 525). Throws core::InputError for E <= 0 or nu outside
    /// (-1, 0.5].
    static HertzMindlinParams fromMaterials(double youngsA, double poissonA, double youngsB,
                                            double poissonB, double restitution, double friction,
                                            double rollingFriction = 0.0);
};

/// The model: with a = sqrt(R_eff delta), S_n = 2 E* a, S_t = 8 G* a,
/// beta = ln e / sqrt(ln^2 e + pi^2), on j:
///   F_n = (4/3) E* a delta - gamma_n v_n,   gamma_n = -2 sqrt(5/6) beta sqrt(S_n m_eff)
///   F_t = tangentialForce(k_t = S_t, c_t = -2 sqrt(5/6) beta sqrt(S_t m_eff),
///                         limit = mu max(F_n, 0)), a sliding spring truncated to its own
///                         share of the capped force (SlipTruncation::SpringOnly).
/// With this damping (proportional to delta^(1/4)) the restitution does not depend on the
/// impact velocity (Antypov & Elliott 2011); measured within 1e-4 of e for e = 0.1-0.9.
class HertzMindlin {
public:
    using Params = HertzMindlinParams;

    /// Throws core::InputError naming the type pair if a parameter is out of range.
    explicit HertzMindlin(MaterialTable<HertzMindlinParams> materials);

    /// Inline: the fused contact loop runs it once per contact and step.
    ContactResponse operator()(ContactState const& s, core::Vec3& spring, core::Vec3& rolling,
                               double dt) const;

    [[nodiscard]] MaterialTable<HertzMindlinParams> const& materials() const { return m_materials; }
    /// Whether some pair of materials has model C's rolling spring.
    [[nodiscard]] bool hasRollingSpring() const { return m_rollingSpring; }
    /// Duration of an elastic impact at relative normal velocity `impactVelocity`:
    /// 2.87 (m_eff^2 / (R_eff E*^2 v))^(1/5) (Johnson, "Contact Mechanics", 1985, sec. 11.4;
    /// the constant is 2.868) [time].
    static double contactTime(HertzMindlinParams const& p, double effectiveMass,
                              double effectiveRadius, double impactVelocity);

private:
    MaterialTable<HertzMindlinParams> m_materials;
    MaterialTable<double> m_beta; ///< -2 sqrt(5/6) beta per pair (>= 0)
    bool m_rollingSpring = false;
};

static_assert(ContactModel<HertzMindlin>);

inline ContactResponse HertzMindlin::operator()(ContactState const& s, core::Vec3& spring,
                                                core::Vec3& rolling, double dt) const {
    HertzMindlinParams const& p = m_materials(s.typeI, s.typeJ);
    double const damping = m_beta(s.typeI, s.typeJ);
    double const a = std::sqrt(s.effectiveRadius * s.penetration);
    double const sn = 2.0 * p.effectiveYoungsModulus * a;
    double const st = 8.0 * p.effectiveShearModulus * a;
    double const vn = s.relativeVelocity.dot(s.normal);
    core::Vec3 const vt = s.relativeVelocity - vn * s.normal;
    double const fn = (4.0 / 3.0) * p.effectiveYoungsModulus * a * s.penetration -
                      damping * std::sqrt(sn * s.effectiveMass) * vn;

    ContactResponse r;
    r.force = fn * s.normal;
    // k_t ~ a but c_t ~ sqrt(a): a sliding spring keeps no dashpot share (SlipTruncation).
    r.force += tangentialForce(spring, s.normal, vt, st, damping * std::sqrt(st * s.effectiveMass),
                               p.friction * std::max(fn, 0.0), dt, SlipTruncation::SpringOnly);
    // Model C's default k_r from the contact's current normal stiffness S_n (k_r ~ a too).
    r.torque = rollingResistance(s, rolling, p.rollingFriction, p.rollingSpring, sn, fn, dt,
                                 SlipTruncation::SpringOnly);
    return r;
}

} // namespace regolith::particles
