#pragma once
/// The time-step guard: refuses a dt above a tenth of the shortest contact duration, the
/// usual stability and accuracy bound for explicit DEM (Cundall & Strack 1979; O'Sullivan &
/// Bray, Eng. Comput. 21 (2004) 278).
#include "core/mpi/Comm.hpp"
#include "particles/kernels/ContactLaw.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <limits>
#include <string>

namespace regolith::particles {

/// The shortest contact duration among a set of particles, and where it comes from.
struct ContactTimeEstimate {
    double contactTime = std::numeric_limits<double>::infinity(); ///< t_c [time]
    std::string parameter;     ///< the scene key t_c was computed from, e.g. "contact.stiffness"
    double parameterValue = 0; ///< its value
    double mass = 0.0;         ///< the smallest mass of the pair that gave t_c [mass]
    Uid uid = kInvalidUid;     ///< the particle with that mass
};

/// Linear model: for every pair of types (a, b) among the movable (not Fixed) particles,
/// t_c = pi sqrt(m_eff / k), the undamped contact duration, with m_eff = m_a m_b / (m_a + m_b),
/// m_a the smallest mass of type a (so m_min / 2 for one type); the shortest. Undamped: the
/// damped duration pi / sqrt(k/m_eff - gamma^2) grows without bound as the restitution goes
/// to 0, while the explicit step stays stable only for omega_0 dt < 2 (sqrt(1 + zeta^2) -
/// zeta), 0.83 at critical damping; t_c / 10 gives omega_0 dt = 0.31 at any restitution (a
/// review found dt = damped t_c / 10 blowing up at e = 1e-6, and "auto" rebounding at 0.64).
/// Infinite without movable particles. Throws core::InputError for a type index outside the
/// model's table. Not collective.
ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, SpringDashpot const& model);

/// Hertz model: as above with HertzMindlin::contactTime, the particle of smallest mass of
/// each type giving m and R (R_eff = r_a r_b / (r_a + r_b)), at the stated relative impact
/// velocity `impactVelocity` > 0 [length/time] — the largest expected, since t_c shrinks as
/// v^(-1/5). Not collective.
ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, HertzMindlin const& model,
                                        double impactVelocity);

/// A contact law of one's own: as above with ContactLaw::contactTime for every pair of the
/// types present. Not collective.
ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, ContactLaw const& law);
inline ContactTimeEstimate estimateContactTime(ParticleStorage const& ps,
                                               CustomContact const& model) {
    return estimateContactTime(ps, model.law());
}

/// The shortest of every rank's `local` estimate (ties: smaller uid), identical on every
/// rank. COLLECTIVE over `comm`.
ContactTimeEstimate shortestContactTime(core::Comm const& comm, ContactTimeEstimate const& local);

/// Throws core::InputError if dt is not positive and finite, or if dt > t_c / 10 and not
/// `allowUnstable`:
/// "time.dt = X exceeds t_c/10 = Y (t_c = Z from contact.stiffness = K and the smallest mass
/// M, uid U); reduce time.dt or set time.allow_unstable = true".
/// Not collective; call it with the result of shortestContactTime so all ranks agree.
void checkTimeStep(double dt, ContactTimeEstimate const& estimate, bool allowUnstable);

} // namespace regolith::particles
