#pragma once
/// The rigid motion of a wall, a function of time alone (so every rank, and a restarted run,
/// puts the wall in the same place): a constant translation velocity plus a sinusoidal shake
/// (LIGGGHTS's `wiggle`), and a constant rotation about an axis through `centre`.
#include "core/math/Vec3.hpp"

#include <cmath>
#include <numbers>

namespace regolith::particles {

struct WallMotion {
    core::Vec3 velocity = core::Vec3::Zero();        ///< constant translation [length/time]
    core::Vec3 angularVelocity = core::Vec3::Zero(); ///< about `centre` [rad/time]
    core::Vec3 centre = core::Vec3::Zero();          ///< the rotation axis point at time 0
    /// The shake: a displacement amplitude * sin(2 pi frequency t) [length], [1/time].
    core::Vec3 amplitude = core::Vec3::Zero();
    double frequency = 0.0;

    [[nodiscard]] bool moves() const {
        return !velocity.isZero(0.0) || !angularVelocity.isZero(0.0) ||
               (!amplitude.isZero(0.0) && frequency != 0.0);
    }
    /// How far the wall (and `centre`) has been translated at time t [length].
    [[nodiscard]] core::Vec3 displacement(double t) const {
        return velocity * t + amplitude * std::sin(2.0 * std::numbers::pi * frequency * t);
    }
    /// The translation velocity at time t [length/time].
    [[nodiscard]] core::Vec3 velocityAt(double t) const {
        double const w = 2.0 * std::numbers::pi * frequency;
        return velocity + amplitude * (w * std::cos(w * t));
    }
    /// The rotation from time 0 to time t: |omega| t about omega.
    [[nodiscard]] core::Quat rotation(double t) const {
        double const rate = angularVelocity.norm();
        if (!(rate > 0.0))
            return core::Quat::Identity();
        return core::Quat(Eigen::AngleAxisd(rate * t, angularVelocity / rate));
    }
};

} // namespace regolith::particles
