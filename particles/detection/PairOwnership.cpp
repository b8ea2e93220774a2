#include "particles/detection/PairOwnership.hpp"

#include <algorithm>

namespace regolith::particles {

Settled settleOwnership(core::Vec3 const& mid, double reach, core::AABB const& region,
                        PeriodicFrame const& frame) {
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
        // Where the rule emits along this axis: the region, and on a periodic axis the domain
        // too (a point outside it wraps to another image: ContactDetector's `image(i) == -o`).
        double lo = region.min[a], hi = region.max[a];
        if (frame.periodic[static_cast<std::size_t>(a)]) {
            lo = std::max(lo, frame.domain.min[a]);
            hi = std::min(hi, frame.domain.max[a]);
        }
        double const below = mid[a] - reach, above = mid[a] + reach;
        if (above < lo || below > hi) // NaN compares false: Open below
            return Settled::Never;
        if (!(below > lo && above < hi))
            inside = false;
    }
    return inside ? Settled::Always : Settled::Open;
}

} // namespace regolith::particles
