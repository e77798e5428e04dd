// Motion of an instance over the frames of a scene (`revdist scene --frames`):
// a pose as a function of the frame number f = 0, 1, 2, ... (README, "Scenes").
#pragma once
#include <cmath>

#include "core/pose.h"

namespace revdist {

// All rates are per frame. At frame f an instance's pose is
//   translation(f) = translation + velocity f + acceleration f^2 / 2
//                    + wave_amplitude sin(2 pi f / wave_period + wave_phase)
//   rotation(f)    = exp(spin f) * rotation    (spin: a world axis times radians per frame,
//                                               about the instance's own origin)
// Frame 0 is the pose as given, so readers that ignore motion see frame 0.
struct InstanceMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();
  Vec3 spin = Vec3::Zero();
  Vec3 wave_amplitude = Vec3::Zero();
  double wave_period = 1.0;  // frames, > 0
  double wave_phase = 0.0;   // radians

  bool moving() const {
    return !velocity.isZero(0) || !acceleration.isZero(0) || !spin.isZero(0) || !wave_amplitude.isZero(0);
  }
};

// The pose at frame f. The quaternion stays a quaternion (the exact engine's
// rational rotation M(q)/|q|^2 applies to every frame's pose as well).
inline Pose pose_at_frame(const Pose& p0, const InstanceMotion& m, double f) {
  if (!m.moving() || f == 0) return p0;
  Pose p = p0;
  const double wave = std::sin(2 * M_PI * f / m.wave_period + m.wave_phase) - std::sin(m.wave_phase);
  p.translation = p0.translation + f * m.velocity + 0.5 * f * f * m.acceleration + wave * m.wave_amplitude;
  const double angle = m.spin.norm() * f;
  if (angle > 0) {
    const Vec3 axis = m.spin.normalized();
    const double s = std::sin(0.5 * angle), w = std::cos(0.5 * angle);
    const double a[4] = {w, s * axis.x(), s * axis.y(), s * axis.z()};
    const auto& b = p0.q;  // Hamilton product a * b
    p.q = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
           a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
           a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
           a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  }
  return p;
}

}  // namespace revdist
