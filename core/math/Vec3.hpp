#pragma once
/// Small fixed-size geometry types on Eigen.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace regolith::core {

using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

} // namespace regolith::core
