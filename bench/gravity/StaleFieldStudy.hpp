#pragma once
/// The update threshold (gravity/update/UpdatePolicy) as one more point of gravity_bench:
/// the force error of a field kept while grains move, against the time per step it saves.
///
/// Motion: each grain moves along its own random direction at its own speed, uniform in
/// [0, 1] × the fastest (independent motion: the worst case for a stale field; a rigid
/// motion of the whole body would change the field far less). The policy recomputes when the
/// fastest grain has moved `threshold`, so the largest error comes just before that update:
/// the error reported is the one of the field of the old positions at positions moved that far,
/// against the exact field there.
///
/// Time per step, amortised: the policy's own check every step (UpdatePolicy::due, timed)
/// plus the evaluation once every threshold / stepDisplacement steps (stepDisplacement: how
/// far the fastest grain moves in one step).
#include "core/mpi/Comm.hpp"
#include "gravity/common/ForceError.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/samples/SyntheticBodies.hpp"

#include <cstddef>
#include <span>

namespace regolith::bench {

struct StalePoint {
    double threshold = 0.0; ///< m
    double stepsPerUpdate = 1.0;
    double dueSeconds = 0.0;  ///< one UpdatePolicy::due() over all grains, wall
    double wallSeconds = 0.0; ///< per step, amortised
    double cpuSeconds = 0.0;  ///< per step, amortised (the check counted at its wall time)
    gravity::ErrorStats error;
};

class StaleFieldStudy {
public:
    /// `grains`: ALL grains (one rank: the study needs every grain's motion); `sample`:
    /// indices into `grains` where the error is measured. Directions and speeds are
    /// deterministic for `seed`. Not collective.
    StaleFieldStudy(gravity::samples::Body const& grains, std::span<std::size_t const> sample,
                    unsigned seed = 7);

    /// The point for `threshold` (m) of a base method whose field at the unmoved grains is
    /// `stale` (all grains) and whose evaluation takes `evalWall` / `evalCpu` seconds.
    /// COLLECTIVE over `comm` (the error statistics; one rank expected).
    StalePoint point(core::Comm const& comm, double threshold, double stepDisplacement,
                     gravity::AccelView stale, double evalWall, double evalCpu) const;

private:
    gravity::samples::Body const* m_grains;
    std::span<std::size_t const> m_sample;
    std::vector<double> m_ux, m_uy, m_uz; ///< velocity of each grain / the fastest's speed
};

} // namespace regolith::bench
