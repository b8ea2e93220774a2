#pragma once
/// Semi-implicit (symplectic) Euler: velocities from the new forces first, then positions
/// from the new velocities. First order, symplectic for velocity-independent forces.
#include "particles/integration/Integrator.hpp"

namespace regolith::particles {

struct SemiImplicitEuler {
    /// Nothing: the whole step happens after the forces are known.
    double preForce(ParticleStorage& /*ps*/, double /*dt*/, core::Vec3 const& /*gravity*/) const {
        return 0.0;
    }
    /// v += dt (F/m + g); x += dt v; omega += dt tau / I; q rotated by omega dt (masters that
    /// are not Fixed). Units: dt [time], gravity [length/time^2]. Returns the largest distance
    /// a copy moved (Integrator).
    double postForce(ParticleStorage& ps, double dt, core::Vec3 const& gravity) const;
};

static_assert(Integrator<SemiImplicitEuler>);

} // namespace regolith::particles
