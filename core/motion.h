// Motion of an instance over the frames of a scene (`revdist scene --frames`):
// a pose as a function of the frame number f = 0, 1, 2, ... (README, "Scenes").
#pragma once
#include <algorithm>
#include <cmath>

#include "core/pose.h"

namespace revdist {

// All rates are per frame. At frame f an instance's pose is
//   translation(f) = translation + velocity f + acceleration f^2 / 2
//                    + wave_amplitude sin(2 pi f / wave_period + wave_phase)
//   rotation(f)    = exp(spin f) * rotation    (spin: a world axis times radians per frame,
//                                               about the instance's own origin)
//   time(f)        = time + time_rate f, reflected at 0 and K - 1 (keyframed solids:
//                    the shape runs back and forth through its keyframes)
// Frame 0 is the pose as given, so readers that ignore motion see frame 0.
struct InstanceMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();
  Vec3 spin = Vec3::Zero();
  Vec3 wave_amplitude = Vec3::Zero();
  double wave_period = 1.0;  // frames, > 0
  double wave_phase = 0.0;   // radians
  double time_rate = 0.0;    // keyframe time per frame (keyframed solids only)

  bool moving() const {
    return !velocity.isZero(0) || !acceleration.isZero(0) || !spin.isZero(0) || !wave_amplitude.isZero(0);
  }
};

// The keyframe time at frame f of an instance at time t0 of a solid with keyframes 0..last.
inline double time_at_frame(double t0, const InstanceMotion& m, double f, double last) {
  if (m.time_rate == 0 || f == 0 || !(last > 0)) return t0;
  const double t = std::fmod(std::abs(t0 + m.time_rate * f), 2 * last);  // period 2 last, even
  return std::min(t <= last ? t : 2 * last - t, last);
}

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
