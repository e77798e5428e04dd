// Vector vocabulary shared by every part of revdist: fixed-size Eigen vectors.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace revdist {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace revdist
