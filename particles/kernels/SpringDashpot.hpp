#pragma once
/// Linear spring-dashpot contact model with a tangential history spring, Coulomb friction and
/// optional rolling resistance (Cundall & Strack, Geotechnique 29 (1979) 47; damping from the
/// restitution coefficient as in Schwager & Poeschel, Granular Matter 9 (2007) 465).
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/MaterialTable.hpp"
#include "particles/kernels/TangentialSpring.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::particles {

/// Parameters of one pair of materials.
struct LinearContactParams {
    double stiffness = 0.0;           ///< k_n [force/length], > 0
    double tangentialStiffness = 0.0; ///< k_t [force/length], >= 0 (2/7 k_n is common)
    double restitution = 1.0;         ///< normal coefficient of restitution e, in (0, 1]
    double friction = 0.0;            ///< Coulomb coefficient mu >= 0
    /// Tangential damping c_t = ratio * c_n (LAMMPS gran/hooke/history uses 1/2).
    double tangentialDampingRatio = 0.5;
    double rollingFriction = 0.0; ///< mu_r >= 0, dimensionless (0: no rolling resistance)
    RollingSpring rollingSpring;  ///< model C if enabled, else model A (TangentialSpring.hpp)
};

/// gamma / omega_0 = -ln e / sqrt(pi^2 + ln^2 e): the damping that makes a free two-body
/// collision end (overlap back to zero) with relative normal velocity ratio e. Precondition:
/// 0 < e <= 1.
double dampingRatioFromRestitution(double restitution);

/// The model: on j, F = (k_n delta - c_n v_n) n + F_t with c_n = 2 m_eff gamma,
/// gamma = -ln(e) sqrt(k_n/m_eff) / sqrt(pi^2 + ln^2 e), v_n = v_rel . n (negative when
/// approaching), and F_t from tangentialForce with k_t, c_t = ratio * c_n, limit
/// mu * max(k_n delta - c_n v_n, 0), and the couple of rollingResistance. The normal force is not
/// clamped at zero: the analytic restitution e = exp(-gamma t_c) holds for the unclamped
/// oscillator, whose force turns slightly attractive just before separation (Schwager & Poeschel
/// 2007 discuss the clamped variant, which has a different e).
class SpringDashpot {
public:
    using Params = LinearContactParams;

    /// Throws core::InputError naming the type pair if a parameter is out of range.
    explicit SpringDashpot(MaterialTable<LinearContactParams> materials);

    /// Inline: the fused contact loop runs it once per contact and step.
    ContactResponse operator()(ContactState const& s, core::Vec3& spring, core::Vec3& rolling,
                               double dt) const;

    [[nodiscard]] MaterialTable<LinearContactParams> const& materials() const {
        return m_materials;
    }
    /// gamma / omega_0 of the pair of types (a, b) (dampingRatioFromRestitution).
    [[nodiscard]] double dampingRatio(std::uint32_t a, std::uint32_t b) const {
        return m_dampingRatio(a, b);
    }
    /// Whether some pair of materials has model C's rolling spring (then every contact keeps a
    /// rolling entry in its history).
    [[nodiscard]] bool hasRollingSpring() const { return m_rollingSpring; }
    /// Duration of a free normal collision: pi / sqrt(k/m_eff - gamma^2) [time].
    static double contactTime(LinearContactParams const& p, double effectiveMass);
    /// The same without the dashpot, pi sqrt(m_eff / k) [time]: the time scale of the explicit
    /// step's stability (TimeStepGuard), which the damped duration overstates without bound
    /// as the restitution goes to 0.
    static double undampedContactTime(LinearContactParams const& p, double effectiveMass);

private:
    MaterialTable<LinearContactParams> m_materials;
    MaterialTable<double> m_dampingRatio; ///< dampingRatioFromRestitution per pair
    bool m_rollingSpring = false;
};

static_assert(ContactModel<SpringDashpot>);

inline ContactResponse SpringDashpot::operator()(ContactState const& s, core::Vec3& spring,
                                                 core::Vec3& rolling, double dt) const {
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
    r.torque =
        rollingResistance(s, rolling, p.rollingFriction, p.rollingSpring, p.stiffness, fn, dt);
    return r;
}

} // namespace regolith::particles
