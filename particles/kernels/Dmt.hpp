#pragma once
/// DMT adhesion (Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53 (1975) 314): the
/// Hertz–Mindlin contact plus a constant pull of 2 pi gamma R* while the grains overlap,
///
///     F_n = (4/3) E* sqrt(R*) delta^(3/2) - damping - 2 pi gamma R*,
///
/// gamma the surface energy in the convention of the pull-off force 2 pi gamma R* (the work of
/// adhesion; LAMMPS's `cohesion` of `dmt` is gamma / 2), R* = r_i r_j / (r_i + r_j). The pull
/// is largest at delta -> 0, so two grains pulled apart slowly part at a load of 2 pi gamma R*
/// (the pull-off force). It acts in contact only (LAMMPS's `dmt`): no range beyond touching.
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/HertzMindlin.hpp"

#include <numbers>

namespace regolith::core {
class ConfigTable;
}

namespace regolith::particles {

class Dmt {
public:
    /// Throws core::InputError unless surfaceEnergy >= 0 and finite.
    Dmt(HertzMindlin elastic, double surfaceEnergy);

    ContactResponse operator()(ContactState const& s, core::Vec3& spring, core::Vec3& rolling,
                               double dt) const {
        ContactResponse r = m_elastic(s, spring, rolling, dt);
        r.force -= pullOff(s.effectiveRadius) * s.normal;
        return r;
    }
    /// 2 pi gamma R* [force].
    [[nodiscard]] double pullOff(double effectiveRadius) const {
        return 2.0 * std::numbers::pi * m_surfaceEnergy * effectiveRadius;
    }
    [[nodiscard]] bool hasRollingSpring() const { return m_elastic.hasRollingSpring(); }
    [[nodiscard]] HertzMindlin const& elastic() const { return m_elastic; }

    /// contact.surface_energy of the scene's [contact] (>= 0, required); throws
    /// core::InputError naming the key.
    [[nodiscard]] static double surfaceEnergyFromScene(core::ConfigTable const& contact);

private:
    HertzMindlin m_elastic;
    double m_surfaceEnergy;
};

static_assert(ContactModel<Dmt>);

/// Hertz–Mindlin's contact time at the impact speed (the adhesion does not shorten it).
inline ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, Dmt const& m,
                                               double impactVelocity) {
    return estimateContactTime(ps, m.elastic(), impactVelocity);
}

struct ContactModelEntry;
/// contact.model = "dmt" (ContactModelRegistry.hpp): Hertz–Mindlin's materials and
/// contact.surface_energy.
[[nodiscard]] ContactModelEntry dmtEntry();

} // namespace regolith::particles
