#include "apps/spin_up/PileMeasures.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regolith::apps {

using core::Vec3;

double PileMeasures::bulkDensity() const {
    return mass / (4.0 / 3.0 * std::numbers::pi * axes[0] * axes[1] * axes[2]);
}

double PileMeasures::bulkRadius() const {
    return std::cbrt(axes[0] * axes[1] * axes[2]);
}

double PileMeasures::criticalSpin(double G) const {
    return std::sqrt(4.0 / 3.0 * std::numbers::pi * G * bulkDensity());
}

PileMeasures measurePile(std::span<MasterRecord const> grains, Vec3 const& guess, double radius,
                         Vec3 const& axis) {
    PileMeasures p;
    double mass = 0.0;
    Vec3 moment = Vec3::Zero();
    for (MasterRecord const& g : grains)
        if ((g.position - guess).norm() <= radius) {
            mass += g.mass;
            moment += g.mass * g.position;
        }
    if (!(mass > 0.0))
        return p;
    p.centre = moment / mass;
    Vec3 L = Vec3::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (MasterRecord const& g : grains) {
        Vec3 const r = g.position - p.centre;
        if (r.norm() > radius) {
            p.outsideMass += g.mass;
            continue;
        }
        double const own = 0.4 * g.mass * g.radius * g.radius; // a solid sphere's moment
        p.mass += g.mass;
        L += g.mass * r.cross(g.velocity) + own * g.angularVelocity;
        inertia += (own + g.mass * r.squaredNorm()) * Eigen::Matrix3d::Identity() -
                   g.mass * r * r.transpose();
    }
    Vec3 const n = axis.normalized();
    p.spin = L.dot(n) / n.dot(inertia * n);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal;
    principal.computeDirect(inertia, Eigen::EigenvaluesOnly); // closed form: no iteration
    Eigen::Vector3d const I = principal.eigenvalues();        // ascending
    double const k = 5.0 / (2.0 * p.mass);
    p.axes = {std::sqrt(std::max(0.0, k * (I[1] + I[2] - I[0]))),
              std::sqrt(std::max(0.0, k * (I[0] + I[2] - I[1]))),
              std::sqrt(std::max(0.0, k * (I[0] + I[1] - I[2])))};
    return p;
}

} // namespace regolith::apps
