#include "particles/detection/PeriodicFrame.hpp"

#include "core/Error.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestGeometry.hpp"

#include <cmath>
#include <string>

namespace regolith::particles {

PeriodicFrame::PeriodicFrame(domain::ForestGeometry const& geometry)
    : domain(geometry.domain())
    , periodic(geometry.periodic()) {}

PeriodicFrame::PeriodicFrame(domain::BlockForest const& forest)
    : domain(forest.domain())
    , periodic(forest.periodic())
    , wrapped(wrappedAxes(forest)) {}

std::array<bool, 3> wrappedAxes(domain::BlockForest const& forest) {
    std::array<bool, 3> out{};
    for (std::size_t a = 0; a < 3; ++a)
        out[a] = forest.periodic()[a] && forest.spannedBySubdomains()[a];
    return out;
}

core::Vec3 PeriodicFrame::period() const {
    core::Vec3 out = core::Vec3::Zero();
    for (int a = 0; a < 3; ++a)
        if (periodic[static_cast<std::size_t>(a)])
            out[a] = domain.max[a] - domain.min[a];
    return out;
}

core::Vec3 PeriodicFrame::wrapPeriod() const {
    core::Vec3 out = period();
    for (int a = 0; a < 3; ++a)
        if (!wrapped[static_cast<std::size_t>(a)])
            out[a] = 0.0;
    return out;
}

std::pair<core::Vec3, CopyImage> PeriodicFrame::wrapOutside(core::Vec3 const& p) const {
    core::Vec3 w = p;
    CopyImage image = kNoImage;
    for (int a = 0; a < 3; ++a) {
        auto const axis = static_cast<std::size_t>(a);
        if (!periodic[axis])
            continue;
        if (!std::isfinite(domain.min[a]) || !std::isfinite(domain.max[a]) ||
            !(domain.max[a] > domain.min[a]))
            throw core::Error("PeriodicFrame: periodic axis " + std::to_string(a) +
                              " needs a finite domain with max > min");
        if (!std::isfinite(p[a]))
            throw core::Error("PeriodicFrame: the point is not finite on a periodic axis");
        auto const [o, x] = domain::wrapOnAxis(domain.min[a], domain.max[a], p[a]);
        if (o < -kMaxImage || o > kMaxImage)
            throw core::Error("PeriodicFrame: point lies " + std::to_string(o) +
                              " periods away on axis " + std::to_string(a) + ", beyond +-" +
                              std::to_string(kMaxImage));
        w[a] = x;
        image[axis] = static_cast<std::int8_t>(o);
    }
    return {w, image};
}

} // namespace regolith::particles
