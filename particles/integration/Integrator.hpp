#pragma once
/// The integrator concept; the rotation update the integrators share is in Rotation.hpp.
#include "core/math/Vec3.hpp"
#include "particles/integration/Rotation.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>

namespace regolith::particles {

/// The largest displacement of the copies an integrator moved, kept in its loop without a
/// branch: a running maximum, and a running sum that turns NaN or infinite if some position
/// did (the maximum skips a NaN; the sum does not).
class LargestMove {
public:
    void add(core::Vec3 const& before, core::Vec3 const& after) {
        double const d2 = (after - before).squaredNorm();
        m_squared = std::max(m_squared, d2);
        m_sum += d2;
    }
    /// The distance [length]; +inf if some displacement was not finite.
    [[nodiscard]] double distance() const {
        return std::isfinite(m_sum) ? std::sqrt(m_squared)
                                    : std::numeric_limits<double>::infinity();
    }

private:
    double m_squared = 0.0;
    double m_sum = 0.0;
};

/// A time integrator split around the force computation, so that one loop serves every
/// scheme (mesa_pd's VelocityVerletPreForceUpdate / PostForceUpdate):
///
///     integrator.preForce(ps, dt, g);   // uses the forces of the previous step
///     ps.resetForces(); detect; evaluateContacts; (reduce shadow forces to masters)
///     integrator.postForce(ps, dt, g);  // uses the new forces
///
/// Both move only masters that are not Fixed; `gravity` is an acceleration [length/time^2].
/// Forces must survive from postForce to the next preForce (they travel with a migrating
/// particle). Each returns the largest distance it moved a copy (0 if it moved none; +inf if
/// some position is not finite): summed over the calls since a neighbour list or a sync skin
/// recorded its reference positions, a bound on every copy's displacement from them, so that
/// those need not compare every position each step (DemStep::step).
template <class I>
concept Integrator = requires(I const& integrator, ParticleStorage& ps, double dt,
                              core::Vec3 const& gravity) {
    { integrator.preForce(ps, dt, gravity) } -> std::same_as<double>;
    { integrator.postForce(ps, dt, gravity) } -> std::same_as<double>;
};

} // namespace regolith::particles
