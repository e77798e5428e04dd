// Circle-circle minimum distance, closest pair and binormal lines in double
// (paper section 3.2 and Appendix A). The leaf kernel of the distance query.
#pragma once
#include <vector>

#include "core/circle3.h"

namespace revdist {

// A binormal line of two circles: a critical pair (p_a on a, p_b on b, p_a != p_b)
// of the squared distance, on the near or the far branch.
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
  // >= 0. Computed as sqrt(Z^2 + (ρ - R)^2), so touching and intersecting circles
  // give a few ε·scale, not exactly 0: the fast engine does not decide contact.
  double distance = 0.0;
  Vec3 point_a = Vec3::Zero();  // a closest point on a (world frame)
  Vec3 point_b = Vec3::Zero();  // a closest point on b
  CircleCircleStatus status = CircleCircleStatus::ok;
  // -1 when there are infinitely many closest pairs. Otherwise 0, meaning "not
  // computed here": the count costs a degree-8 root isolation (several µs), so it
  // is computed on request by circle3_circle3_binormals (every pair of circles
  // has at least one binormal line, its farthest pair, so 0 is never a count).
  int binormals = 0;
};

// Minimum distance between circles a and b (radius 0 = a point), with one
// closest pair and the status. Never throws; degenerate configurations are
// reported as data. Inputs must be finite with non-zero normals (any length).
// Symmetric: swapping a and b swaps the points and gives the same distance bit
// for bit. Scaling both circles by a power of two scales the answer exactly.
// Accuracy: within a few ε·scale of the true distance, scale =
// max(r_a, r_b, |c_a - c_b|) (tests: 1e-13·scale random, 1e-10·scale degenerate).
Circle3Circle3Result circle3_circle3_distance(const Circle3& a, const Circle3& b);

// The same distance alone (no points, no status): the general method skips
// its tests for infinitely many closest pairs. For lower bounds.
double circle3_circle3_distance_value(const Circle3& a, const Circle3& b);

// The plane frame of every circle about one normal (a solid's parts all lie
// about its axis), prepared once: circle3_circle3_distance_value of circles
// a and b whose normals are fa's and fb's gives the same value, bit for bit,
// without rebuilding the two frames at each call.
// (A circle passed with frame f must have the normal f was made from.)
struct CircleNormalFrame {
  Vec3 n, u, v;  // unit normal and in-plane basis, u x v = n
};
CircleNormalFrame circle_normal_frame(const Vec3& normal);
double circle3_circle3_distance_value(const Circle3& a, const CircleNormalFrame& fa, const Circle3& b,
                                      const CircleNormalFrame& fb);

// The binormal lines of a and b, one entry per line, so size() is their count
// (README, `circles`): a line is a segment PQ, P on a, Q on b, normal to both
// (to a point circle: any direction), of length above 64ε·2^e (2^e the power
// of two just above max(radii, max |C_a - C_b| component); shorter ones are
// contact points). A near and a far line at one point of b are two lines; the
// lines from a point of b on a's axis are those in the plane normal to b there.
// Roots of one branch that the rounding cannot separate (the branch derivative
// stays within its rounding between them) are one line. *infinitely_many is set
// when the lines form a continuum (coaxial, Villarceau, meridian circles, a
// point on the other's axis), and whenever circle3_circle3_distance reports
// infinitely_many closest pairs of two circles with the closest point of b off
// a's axis (they then move along b; both decided to rounding); the vector is
// then empty. Slower than circle3_circle3_distance (a degree-8 root
// isolation); used by the CLI and the tests, not on the hot path.
std::vector<CircleBinormal> circle3_circle3_binormals(const Circle3& a, const Circle3& b,
                                                      bool* infinitely_many = nullptr);

// Every binormal line of a and b, including several at one point Q of b (near
// and far, or the ones through a point of a's axis; at a point Q with a whole
// cone of lines, one representative). Same infinitely_many convention.
std::vector<CircleBinormal> circle3_circle3_binormal_lines(const Circle3& a, const Circle3& b,
                                                           bool* infinitely_many = nullptr);

// The same, restricted to what a pruning caller needs: at least every binormal
// line shorter than max_len (longer ones may be returned too). The roots are
// sought only on the arcs of b that come within max_len of a (closed-form ball
// bounds on 32 arcs), so a short window costs a fraction of the whole circle.
// *dropped_lb: a lower bound (>= max_len) on the distance from a to the arcs of
// b left out, +inf when none was; in the infinitely-many case nothing is left out.
// arc_test (optional): a further filter on arcs of b, false when no needed
// line ends in the ball (centre, radius) that holds the arc (a Gauss-map
// restriction, paper section 3.3); arcs it drops add nothing to *dropped_lb.
struct BinormalArcTest {
  bool (*keep)(const void* ctx, const Vec3& centre, double radius) = nullptr;
  const void* ctx = nullptr;
};
std::vector<CircleBinormal> circle3_circle3_binormal_lines_within(const Circle3& a, const Circle3& b, double max_len,
                                                                  bool* infinitely_many, double* dropped_lb,
                                                                  const BinormalArcTest* arc_test = nullptr);

}  // namespace revdist
