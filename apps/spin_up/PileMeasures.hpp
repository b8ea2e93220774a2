#pragma once
/// What a rubble pile looks like: its mass, centre, spin about an axis, shape (the semi-axes
/// of the uniform ellipsoid with the same principal moments of inertia) and the mass outside
/// it. Pure functions of the grains, summed in the order given (uid order from
/// gatherMastersByUid: the same bits on any rank count).
#include "apps/common/MasterRecord.hpp"
#include "core/math/Vec3.hpp"

#include <array>
#include <span>

namespace regolith::apps {

struct PileMeasures {
    double mass = 0.0;                         ///< grains within the pile's radius
    core::Vec3 centre = core::Vec3::Zero();    ///< their centre of mass
    double spin = 0.0;                         ///< L . n / (n . I . n) about the axis n
    std::array<double, 3> axes{0.0, 0.0, 0.0}; ///< a >= b >= c [length]
    double outsideMass = 0.0;                  ///< grains beyond the radius

    /// Bulk density M / (4/3 pi a b c): grains and pores alike.
    [[nodiscard]] double bulkDensity() const;
    /// The mean radius (a b c)^(1/3) of the equivalent ellipsoid.
    [[nodiscard]] double bulkRadius() const;
    /// The orbital rate at the surface of a sphere of the bulk density, sqrt(4 pi G rho / 3)
    /// (= sqrt(G M / (a b c))): a cohesionless sphere spinning faster sheds its equator.
    [[nodiscard]] double criticalSpin(double G) const;
};

/// The pile: the grains within `radius` of `guess`, centred on their centre of mass (one
/// iteration), spin about the unit `axis` through it. The inertia tensor counts each grain as
/// a solid sphere (2/5 m r^2 about its own centre, its spin in the angular momentum); the
/// equivalent ellipsoid of principal moments I1 <= I2 <= I3 has a^2 = 5 (I2 + I3 - I1) / (2 M),
/// b^2 = 5 (I1 + I3 - I2) / (2 M), c^2 = 5 (I1 + I2 - I3) / (2 M). All zero without grains.
[[nodiscard]] PileMeasures measurePile(std::span<MasterRecord const> grains,
                                       core::Vec3 const& guess, double radius,
                                       core::Vec3 const& axis);

} // namespace regolith::apps
