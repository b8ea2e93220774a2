#include "particles/integration/Integrator.hpp"

#include <Eigen/Geometry>

namespace regolith::particles {

void rotate(core::Quat& q, core::Vec3 const& angularVelocity, double dt) {
    double const w = angularVelocity.norm();
    if (w == 0.0)
        return;
    q = core::Quat(Eigen::AngleAxisd(w * dt, angularVelocity / w)) * q;
    q.normalize();
}

} // namespace regolith::particles
