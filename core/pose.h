// Rigid pose of an instance: rotation from a (not necessarily unit) quaternion
// [w, x, y, z] and a translation. world = R * local + translation (SPEC section 3).
#pragma once
#include <array>

#include "core/vec.h"

namespace revdist {

struct Pose {
  // The quaternion as given; R = M(q) / |q|^2 is exactly orthogonal over the
  // rationals, which the exact engine relies on, so it is never normalised here.
  std::array<double, 4> q = {1.0, 0.0, 0.0, 0.0};
  Vec3 translation = Vec3::Zero();

  // R = M(q) / |q|^2 evaluated in double.
  Mat3 rotation() const {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double n = w * w + x * x + y * y + z * z;
    Mat3 m;
    m << w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
        2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
        2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z;
    return m / n;
  }
  Vec3 apply(const Vec3& p_local) const { return rotation() * p_local + translation; }
};

}  // namespace revdist
