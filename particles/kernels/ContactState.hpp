#pragma once
/// The interface between contact evaluation and contact models: what a model sees of one
/// contact, what it returns, and the concept a model satisfies.
#include "core/math/Vec3.hpp"

#include <concepts>
#include <cstdint>

namespace regolith::particles {

/// The kinematics of one contact between body i and body j (a wall is always i), evaluated
/// at the contact point.
struct ContactState {
    core::Vec3 normal;  ///< unit, from i towards j
    double penetration; ///< overlap > 0 [length]
    /// Velocity of j's material point relative to i's, at the contact point [length/time].
    core::Vec3 relativeVelocity;
    /// omega_j - omega_i [rad/time] (rolling resistance).
    core::Vec3 relativeAngularVelocity;
    double effectiveMass;   ///< 1 / (1/m_i + 1/m_j); m of the sphere against a wall [mass]
    double effectiveRadius; ///< r_i r_j / (r_i + r_j); r of the sphere against a wall [length]
    /// 1/I_i + 1/I_j: bounds the rolling torque so that it cannot reverse the relative
    /// rotation within one step [1/(mass length^2)].
    double inverseInertiaSum;
    std::uint32_t typeI;
    std::uint32_t typeJ;
};

/// A model's answer: acting on j; i receives the opposite (Newton's third law).
struct ContactResponse {
    core::Vec3 force = core::Vec3::Zero();  ///< applied at the contact point [force]
    core::Vec3 torque = core::Vec3::Zero(); ///< pure couple (rolling resistance) [force length]
};

/// A contact force model: a stateless functor that, given the contact's kinematics, its
/// tangential and rolling springs from the history (updated in place) and the time step,
/// returns the force and couple on j; it says whether it uses the rolling spring (model C)
/// at all, so that histories keep one only then.
template <class M>
concept ContactModel = requires(M const& m, ContactState const& s, core::Vec3& spring,
                                core::Vec3& rolling, double dt) {
    { m(s, spring, rolling, dt) } -> std::same_as<ContactResponse>;
    { m.hasRollingSpring() } -> std::convertible_to<bool>;
};

/// A model's batch kernel, where it has one: a specialisation beside the model names its
/// reusable `Workspace`, its pair callback `Pairs<Sink>` and its wall contacts' workspace
/// `Walls` (SpringDashpotBatch.hpp), and the contact loop then evaluates the pairs it finds and
/// the wall contacts a batch at a time (BlockContactLoop.hpp).
template <class M>
struct BatchKernel {};

} // namespace regolith::particles
