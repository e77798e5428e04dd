// Continuous near-contact motion of two solids (the paper's section 5, Figure 12
// and Figure 8 setting): smooth rigid motion with the gap held near a target
// fraction of the pair's size, some frames touching or slightly overlapping.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/profile.h"
#include "core/vec.h"
#include "fast/solid_distance.h"

namespace revdist {

struct MotionOptions {
  int frames = 100;
  std::uint64_t seed = 1;
  // The gap follows clearance * size * (1 + swing * sin(...)): with swing > 1 the
  // dips of the gap go below zero, so those frames overlap by up to
  // (swing - 1) * clearance * size (about 10 % of the frames for swing 1.05).
  double clearance = 1e-2;
  double swing = 1.05;
  int gap_cycles = 3;  // dips of the gap over the motion
};

struct MotionFrame {
  Mat3 R_WA = Mat3::Identity(), R_WB = Mat3::Identity();
  Vec3 t_WA = Vec3::Zero(), t_WB = Vec3::Zero();
  double target = 0.0;    // the planned gap (negative: planned overlap depth along the approach)
  double achieved = 0.0;  // the setup query's distance at this pose (0 for planned overlaps)
  int evaluations = 0;    // setup distance queries spent on this frame
};

// The solid b at frame j in its local frame (R and t are ignored): a deformable
// solid changes shape from frame to frame.
using ShapeAt = std::function<PosedSolid(int frame)>;

// Extent of a profile: the larger of its diameter and height (the size the gap
// is relative to).
double profile_extent(const Profile& p);
// Largest distance of a profile point from the solid's local origin.
double profile_reach(const Profile& p);

// Frames of a smooth motion: both solids turn about fixed random axes, b's
// direction from a circles a on a tilted, wobbling path, and b's distance along
// that direction is solved per frame (Lipschitz steps and safeguarded secant on
// solid_distance, started where the last two frames point) so the gap is within
// 5 % of clearance * size of the target. `a` uses its R and t as the initial pose.
// Deterministic for a given seed.
std::vector<MotionFrame> near_contact_motion(const PosedSolid& a, const ShapeAt& b, const MotionOptions& options);

}  // namespace revdist
