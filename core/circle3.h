// A circle in 3D with a non-unit normal (SPEC section 4). Radius 0 is a point.
#pragma once
#include "core/vec.h"

namespace revdist {

// The normal is kept as given (not normalised): the exact engine converts the
// doubles to rationals losslessly, and |n|^2 stays rational where |n| would not.
struct Circle3 {
  Vec3 center = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double radius = 0.0;
};

}  // namespace revdist
