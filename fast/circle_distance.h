// Circle-circle minimum distance, closest pair and binormal lines in double
// (paper section 3.2 and Appendix A). The leaf kernel of the distance query.
#pragma once
#include <vector>

#include "core/circle3.h"

namespace revdist {

// A binormal line of two circles: a critical pair (p_a on a, p_b on b, p_a != p_b)
// of the squared distance, on the near or the far branch. For a pair that has
// finitely many, each line is reported once.
struct CircleBinormal {
  Vec3 point_a;
  Vec3 point_b;
  double distance = 0.0;
};

enum class CircleCircleStatus {
  ok,               // finitely many closest pairs; point_a/point_b is one of them
  infinitely_many,  // equidistant closest pairs (coaxial, Villarceau, point on the axis, ...)
};

struct Circle3Circle3Result {
  double distance = 0.0;  // >= 0; exactly 0 when the circles are found to meet
  Vec3 point_a = Vec3::Zero();  // a closest point on a (world frame)
  Vec3 point_b = Vec3::Zero();  // a closest point on b
  CircleCircleStatus status = CircleCircleStatus::ok;
  // Number of binormal lines; -1 when there are infinitely many.
  int binormals = 0;
};

// Minimum distance between circles a and b (radius 0 = a point), with one
// closest pair and the status. Never throws; degenerate configurations are
// reported as data. Inputs must be finite with non-zero normals.
Circle3Circle3Result circle3_circle3_distance(const Circle3& a, const Circle3& b);

// All binormal lines of a and b (empty and infinitely_many=true when there are
// infinitely many). Slower than circle3_circle3_distance; used by the CLI and
// the tests, not on the hot path.
std::vector<CircleBinormal> circle3_circle3_binormals(const Circle3& a, const Circle3& b,
                                                      bool* infinitely_many = nullptr);

}  // namespace revdist
