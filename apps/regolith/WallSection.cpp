#include "apps/regolith/WallSection.hpp"

#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/config/ValueChecks.hpp"

#include <fmt/format.h>

#include <array>
#include <string_view>

namespace regolith::apps {

namespace {

using namespace std::string_view_literals;

/// In the order of particles::WallShape.
constexpr std::array kShapeNames{"plane"sv, "rectangle"sv, "disc"sv, "cylinder"sv};
constexpr std::array kSideNames{"inner"sv, "outer"sv};

bool isNonZeroVec3(core::Vec3 const& v) {
    return v.allFinite() && v.norm() > 0.0;
}
constexpr std::string_view kNonZero = "a non-zero vector of 3 finite numbers";
constexpr std::string_view kVector = "an array of 3 finite numbers";
constexpr std::string_view kPositive = "a positive finite length";

/// Fails on the first of `keys` present: the shape has no such key.
void refuseKeys(core::ConfigTable const& t, particles::WallShape shape,
                std::initializer_list<std::string_view> keys) {
    for (std::string_view key : keys)
        if (t.has(key))
            t.fail(key, fmt::format("does not apply to shape = \"{}\"",
                                    kShapeNames[static_cast<std::size_t>(shape)]));
}

} // namespace

void requireRepeatsAlongPeriodicAxes(core::ConfigTable const& t, particles::Wall const& w,
                                     domain::ForestSpec const& forest) {
    using particles::WallShape;
    particles::WallGeometry const& g = w.geometry;
    for (int a = 0; a < 3; ++a) {
        if (!forest.periodic[static_cast<std::size_t>(a)])
            continue;
        core::Vec3 const along = core::Vec3::Unit(a);
        char const axis = "xyz"[a];
        switch (g.shape) {
        case WallShape::Plane:
            if (g.normal[a] != 0.0)
                t.fail("normal", fmt::format("the wall crosses the periodic axis {0} (its normal "
                                             "has a {0} component; domain.periodic): grains "
                                             "leaving through the periodic face would come back "
                                             "behind it; make the normal perpendicular to the "
                                             "periodic axes",
                                             axis));
            break;
        case WallShape::Cylinder:
            if (!g.normal.cross(along).isZero(0.0))
                t.fail("axis", fmt::format("a cylinder in a domain periodic along {0} must lie "
                                           "along {0} (domain.periodic)",
                                           axis));
            break;
        case WallShape::Rectangle:
        case WallShape::Disc:
            t.fail("shape", fmt::format("a {} ends inside the domain, which is periodic along {} "
                                        "(domain.periodic): grains would pass round it through "
                                        "the periodic face; use a plane, or an open domain",
                                        kShapeNames[static_cast<std::size_t>(g.shape)], axis));
        }
        if (!w.motion.angularVelocity.cross(along).isZero(0.0))
            t.fail("angular_velocity",
                   fmt::format("a wall in a domain periodic along {0} may turn about {0} only "
                               "(domain.periodic)",
                               axis));
    }
}

particles::Wall parseWall(core::ConfigTable const& t, std::size_t index) {
    using core::isFiniteVec3;
    using particles::WallShape;
    particles::Wall w;
    particles::WallGeometry& g = w.geometry;
    g.shape = static_cast<WallShape>(t.getChoiceOr("shape", kShapeNames, 0));
    g.point = t.getIf<core::Vec3>("point", isFiniteVec3, kVector);
    bool const cylinder = g.shape == WallShape::Cylinder;
    g.normal = t.getIf<core::Vec3>(cylinder ? "axis" : "normal", isNonZeroVec3, kNonZero);
    g.normal.normalize();
    refuseKeys(t, g.shape, {cylinder ? "normal" : "axis"});
    if (g.shape == WallShape::Rectangle) {
        auto const size = t.getIf<std::array<double, 2>>(
            "size",
            [](auto const& s) {
                return core::isPositiveFinite(s[0]) && core::isPositiveFinite(s[1]);
            },
            "two positive finite side lengths [a, b]");
        g.halfSize[0] = 0.5 * size[0];
        g.halfSize[1] = 0.5 * size[1];
        g.edge = t.getOrIf<core::Vec3>(
            "edge", particles::WallGeometry::anyPerpendicular(g.normal),
            [&](core::Vec3 const& e) {
                return isNonZeroVec3(e) && !e.normalized().cross(g.normal).isZero(1e-12);
            },
            "a vector of 3 finite numbers not parallel to the normal");
        g.edge = (g.edge - g.edge.dot(g.normal) * g.normal).normalized();
    } else {
        refuseKeys(t, g.shape, {"size", "edge"});
    }
    if (g.shape == WallShape::Disc || cylinder)
        g.radius = t.getIf<double>("radius", core::isPositiveFinite, kPositive);
    else
        refuseKeys(t, g.shape, {"radius"});
    if (cylinder)
        g.inner = t.getChoiceOr("side", kSideNames, 0) == 0;
    else
        refuseKeys(t, g.shape, {"side"});
    w.type = parseMaterialType(t);

    particles::WallMotion& m = w.motion;
    m.velocity = t.getOrIf<core::Vec3>("velocity", m.velocity, isFiniteVec3, kVector);
    m.angularVelocity =
        t.getOrIf<core::Vec3>("angular_velocity", m.angularVelocity, isFiniteVec3, kVector);
    m.centre = t.getOrIf<core::Vec3>("axis_point", g.point, isFiniteVec3, kVector);
    m.amplitude = t.getOrIf<core::Vec3>("amplitude", m.amplitude, isFiniteVec3, kVector);
    m.frequency = t.getOrIf<double>("frequency", 0.0, core::isNonNegativeFinite,
                                    "a non-negative finite number of cycles per time");
    if (t.has("amplitude") != t.has("frequency"))
        t.fail(t.has("amplitude") ? "amplitude" : "frequency",
               "a shake needs both amplitude and frequency");
    w.uid = particles::wallUid(index);
    w.centre = m.centre;
    w.velocity = m.velocityAt(0.0);
    return w;
}

} // namespace regolith::apps
