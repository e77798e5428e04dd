// Vector vocabulary shared by every part of revdist: fixed-size Eigen vectors.
#pragma once
#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace revdist {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// The plane's cross product: a.x b.y - a.y b.x.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Distance from p to the segment a-b (to a when the segment is a point).
inline double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace revdist
