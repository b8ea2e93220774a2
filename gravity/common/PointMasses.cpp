#include "gravity/common/PointMasses.hpp"

#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <cmath>

namespace regolith::gravity {

void validatePointMasses(PointMasses const& masses, char const* key) {
    std::size_t const n = masses.size();
    if (masses.y.size() != n || masses.z.size() != n || masses.m.size() != n ||
        (!masses.r.empty() && masses.r.size() != n))
        throw core::InputError(fmt::format("{}: position, mass and radius arrays differ in "
                                           "length ({}, {}, {}, {}, {})",
                                           key, n, masses.y.size(), masses.z.size(),
                                           masses.m.size(), masses.r.size()));
    for (std::size_t i = 0; i < n; ++i) {
        if (!(masses.m[i] >= 0.0) || !std::isfinite(masses.m[i]))
            throw core::InputError(
                fmt::format("{}: mass of grain {} is {} kg; masses must be finite and >= 0", key, i,
                            masses.m[i]));
        if (!std::isfinite(masses.x[i]) || !std::isfinite(masses.y[i]) ||
            !std::isfinite(masses.z[i]))
            throw core::InputError(fmt::format("{}: position of grain {} is not finite", key, i));
        if (!masses.r.empty() && !(masses.r[i] >= 0.0))
            throw core::InputError(fmt::format("{}: radius of grain {} is {}; radii must be >= 0",
                                               key, i, masses.r[i]));
    }
}

void validateFieldOut(FieldOut const& out, std::size_t n) {
    if (out.ax.size() != n || out.ay.size() != n || out.az.size() != n ||
        (!out.phi.empty() && out.phi.size() != n))
        throw core::Error(fmt::format("gravity: output arrays hold {}, {}, {}, {} values for "
                                      "{} grains",
                                      out.ax.size(), out.ay.size(), out.az.size(), out.phi.size(),
                                      n));
}

void validatePointMassesCollective(core::Comm const& comm, PointMasses const& masses,
                                   char const* key) {
    core::agreeOnInputError(comm, [&] { validatePointMasses(masses, key); });
}

} // namespace regolith::gravity
