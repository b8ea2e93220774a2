#include "particles/detection/PairOwnership.hpp"

#include <algorithm>
#include <limits>

namespace regolith::particles {

core::AABB emittingBox(core::AABB const& region, PeriodicFrame const& frame) {
    core::AABB box = region;
    double const inf = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
        if (frame.wrapped[static_cast<std::size_t>(a)]) { // one instance: wherever the point
            box.min[a] = -inf;
            box.max[a] = inf;
        } else if (frame.periodic[static_cast<std::size_t>(a)]) {
            box.min[a] = std::max(box.min[a], frame.domain.min[a]);
            box.max[a] = std::min(box.max[a], frame.domain.max[a]);
        }
    return box;
}

Settled settleOwnership(core::Vec3 const& mid, double reach, core::AABB const& region,
                        PeriodicFrame const& frame) {
    core::AABB const emits = emittingBox(region, frame);
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
        double const lo = emits.min[a], hi = emits.max[a];
        double const below = mid[a] - reach, above = mid[a] + reach;
        if (above < lo || below > hi) // NaN compares false: Open below
            return Settled::Never;
        if (!(below > lo && above < hi))
            inside = false;
    }
    return inside ? Settled::Always : Settled::Open;
}

} // namespace regolith::particles
