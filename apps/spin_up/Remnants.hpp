#pragma once
/// The largest remnant of a pile: the grains linked by friends-of-friends (Davis et al. 1985,
/// ApJ 292, 371), two grains being friends when their surfaces are closer than a gap, which
/// with a gap below a grain radius is the contact network plus grains about to touch. A pure
/// function of the grains (gathered on every rank in uid order: the same answer on any rank
/// count).
#include "apps/common/MasterRecord.hpp"
#include "core/math/Vec3.hpp"

#include <cstddef>
#include <span>

namespace regolith::apps {

struct Remnant {
    double mass = 0.0;                      ///< of the largest cluster (the lowest uid on ties)
    core::Vec3 centre = core::Vec3::Zero(); ///< its centre of mass
    std::size_t grains = 0;                 ///< its grains
    std::size_t clusters = 0;               ///< clusters of any size, single grains included
};

/// Clusters of `grains` whose members are linked by |x_i - x_j| <= r_i + r_j + gap (gap >= 0).
/// Cost O(N) over a hashed grid of cells of the largest linking distance.
[[nodiscard]] Remnant largestRemnant(std::span<MasterRecord const> grains, double gap);

} // namespace regolith::apps
