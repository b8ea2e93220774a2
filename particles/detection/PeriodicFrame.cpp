#include "particles/detection/PeriodicFrame.hpp"

#include "core/Error.hpp"
#include "domain/ForestGeometry.hpp"

#include <cmath>
#include <string>

namespace regolith::particles {

PeriodicFrame::PeriodicFrame(domain::ForestGeometry const& geometry)
    : domain(geometry.domain())
    , periodic(geometry.periodic()) {}

core::Vec3 PeriodicFrame::period() const {
    core::Vec3 out = core::Vec3::Zero();
    for (int a = 0; a < 3; ++a)
        if (periodic[static_cast<std::size_t>(a)])
            out[a] = domain.max[a] - domain.min[a];
    return out;
}

std::pair<core::Vec3, CopyImage> PeriodicFrame::wrapOutside(core::Vec3 const& p) const {
    // A geometry that agrees with the forest's on the periodic axes (the image and wrapped
    // value depend only on min, max and the coordinate) and has a unit box on the others, at
    // whose origin the query is put so that `locate` never rejects it.
    core::AABB box = domain;
    core::Vec3 query = p;
    for (int a = 0; a < 3; ++a) {
        if (periodic[static_cast<std::size_t>(a)]) {
            if (!std::isfinite(domain.min[a]) || !std::isfinite(domain.max[a]) ||
                !(domain.max[a] > domain.min[a]))
                throw core::Error("PeriodicFrame: periodic axis " + std::to_string(a) +
                                  " needs a finite domain with max > min");
        } else {
            box.min[a] = 0.0;
            box.max[a] = 1.0;
            query[a] = 0.0;
        }
    }
    domain::ForestGeometry const geometry(box, {1, 1, 1}, periodic, 0);
    auto const location = geometry.locate(query);
    if (!location)
        throw core::Error("PeriodicFrame: the point is not finite on a periodic axis");
    core::Vec3 w = geometry.wrap(p);
    CopyImage image = kNoImage;
    for (std::size_t a = 0; a < 3; ++a) {
        int const o = location->image[a];
        if (o < -kMaxImage || o > kMaxImage)
            throw core::Error("PeriodicFrame: point lies " + std::to_string(o) +
                              " periods away on axis " + std::to_string(a) + ", beyond +-" +
                              std::to_string(kMaxImage));
        image[a] = static_cast<std::int8_t>(o);
    }
    return {w, image};
}

} // namespace regolith::particles
