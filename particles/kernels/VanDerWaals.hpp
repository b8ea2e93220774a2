#pragma once
/// Van der Waals cohesion between grains as used for regolith (Scheeres et al., Icarus 210
/// (2010) 968; Sánchez & Scheeres, Meteorit. Planet. Sci. 49 (2014) 788): on top of the
/// spring-dashpot's repulsion, an attraction of two spheres across the surface gap s,
///
///     F = A R* / (6 max(s, s_min)^2)      for s < s_c (and in overlap, where s < 0),
///
/// A the Hamaker constant, R* = r_i r_j / (r_i + r_j), s_min the minimum separation (the
/// force stops growing there: F_max = A R* / (6 s_min^2)), s_c the cut-off. The grains attract
/// before they touch, so detection and the shadows reach s_c beyond the radii
/// (interactionRange). Reversible: no history beyond the spring-dashpot's springs, which
/// restart from zero whenever the grains part. Wall contacts act in overlap only.
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/SpringDashpot.hpp"

#include <algorithm>

namespace regolith::core {
class ConfigTable;
}

namespace regolith::particles {

struct VanDerWaalsParams {
    double hamaker = 0.0;       ///< A > 0 [energy]
    double minSeparation = 0.0; ///< s_min > 0 [length]
    double cutoff = 0.0;        ///< s_c > s_min [length]

    /// contact.hamaker, contact.min_separation, contact.cutoff of the scene's [contact];
    /// throws core::InputError naming the key if one is missing or out of range.
    [[nodiscard]] static VanDerWaalsParams fromScene(core::ConfigTable const& contact);
    /// The work to part two touching grains beyond the cut-off, the integral of F from s = 0
    /// to s_c: (A R* / (6 s_min)) (2 - s_min / s_c) [energy]. A pair that parts from touching
    /// with a relative normal speed below sqrt(2 W / m_eff) stays bound.
    [[nodiscard]] double separationWork(double effectiveRadius) const {
        return hamaker * effectiveRadius / (6.0 * minSeparation) * (2.0 - minSeparation / cutoff);
    }
};

class VanDerWaals {
public:
    /// Throws core::InputError naming the parameter if one is out of range.
    VanDerWaals(SpringDashpot repulsion, VanDerWaalsParams params);

    ContactResponse operator()(ContactState const& s, core::Vec3& spring, core::Vec3& rolling,
                               double dt) const {
        double const gap = -s.penetration;
        ContactResponse r;
        if (gap < 0.0) {
            r = m_repulsion(s, spring, rolling, dt);
        } else { // apart: the springs of the next touch start from zero
            spring.setZero();
            rolling.setZero();
        }
        if (gap < m_params.cutoff) {
            double const sep = std::max(gap, m_params.minSeparation);
            r.force -= (m_params.hamaker * s.effectiveRadius / (6.0 * sep * sep)) * s.normal;
        }
        return r;
    }
    [[nodiscard]] bool hasRollingSpring() const { return m_repulsion.hasRollingSpring(); }
    [[nodiscard]] double interactionRange() const { return m_params.cutoff; }
    [[nodiscard]] SpringDashpot const& repulsion() const { return m_repulsion; }
    [[nodiscard]] VanDerWaalsParams const& params() const { return m_params; }

private:
    SpringDashpot m_repulsion;
    VanDerWaalsParams m_params;
};

static_assert(ContactModel<VanDerWaals>);

/// The spring-dashpot's contact time (the attraction does not shorten it).
inline ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, VanDerWaals const& m) {
    return estimateContactTime(ps, m.repulsion());
}

struct ContactModelEntry;
/// contact.model = "vdw" (ContactModelRegistry.hpp): the spring-dashpot's materials and
/// VanDerWaalsParams::fromScene.
[[nodiscard]] ContactModelEntry vanDerWaalsEntry();

} // namespace regolith::particles
