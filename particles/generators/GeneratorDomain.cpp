#include "particles/generators/GeneratorDomain.hpp"

#include <cmath>

namespace regolith::particles {

core::Vec3 GeneratorDomain::wrap(core::Vec3 const& p) const {
    core::Vec3 q = p;
    for (int a = 0; a < 3; ++a) {
        if (!periodic[static_cast<std::size_t>(a)])
            continue;
        double const lo = box.min[a];
        double const hi = box.max[a];
        double const length = hi - lo;
        if (q[a] < lo || q[a] >= hi)
            q[a] -= length * std::floor((q[a] - lo) / length);
        // Rounding of the line above can land exactly on hi or a hair below lo.
        if (q[a] >= hi)
            q[a] = std::nextafter(hi, lo);
        if (q[a] < lo)
            q[a] = lo;
    }
    return q;
}

} // namespace regolith::particles
