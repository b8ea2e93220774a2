#include "gravity/tree/TreeOptions.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace regolith::gravity::tree {

void validate(TreeOptions const& o) {
    if (!(o.theta > 0.0) || !std::isfinite(o.theta))
        throw core::InputError(
            fmt::format("gravity.theta = {}: the opening angle must be > 0", o.theta));
    if (o.theta > 1.0 && !o.allowLargeTheta)
        throw core::InputError(fmt::format(
            "gravity.theta = {}: opening angles above 1 accept cells that contain the grain "
            "they act on (large errors); set gravity.allow_large_theta = true to insist",
            o.theta));
    if (!(o.G > 0.0) || !std::isfinite(o.G))
        throw core::InputError(
            fmt::format("gravity.G = {}: Newton's constant must be finite and > 0", o.G));
    if (!(o.softening >= 0.0) || !std::isfinite(o.softening))
        throw core::InputError(fmt::format(
            "gravity.softening = {}: the softening length must be finite and >= 0 m", o.softening));
    if (o.leafSize < 1)
        throw core::InputError(
            fmt::format("gravity.leaf_size = {}: a leaf holds at least 1 grain", o.leafSize));
    if (o.groupSize < 1)
        throw core::InputError(
            fmt::format("gravity.group_size = {}: a group holds at least 1 grain", o.groupSize));
}

OpeningCriterion parseOpeningCriterion(std::string const& name) {
    if (name == "bmax-offset")
        return OpeningCriterion::BmaxPlusOffset;
    if (name == "bmax")
        return OpeningCriterion::Bmax;
    if (name == "edge-offset")
        return OpeningCriterion::EdgePlusOffset;
    throw core::InputError(fmt::format(
        "gravity.opening = \"{}\": expected \"bmax-offset\", \"bmax\" or \"edge-offset\"", name));
}

} // namespace regolith::gravity::tree
