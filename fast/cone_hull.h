// A proven lower bound on the distance between two conical patches (cones,
// cylinders, flat annuli) that needs no normal lines: the distance between
// their convex hulls (solid frusta), bounded by a separating direction. It is
// well conditioned where the common normals are not (nearly parallel axes,
// where every normal line of one cone is nearly normal to the other).
#pragma once
#include "fast/patch.h"

namespace revdist {

struct ConeHullResult {
  // Proven (rounding included) lower bound on the distance between the two
  // frusta, hence between the patches; <= 0 when the hulls may meet.
  double lower = 0.0;
  // Points of the patches (the hulls' closest points moved onto the lateral
  // surfaces in their meridian planes, to rounding) and their distance, an
  // upper bound on the patch distance; equal to `lower` up to the iteration's
  // accuracy when the hulls' closest points lie on the lateral surfaces (side
  // by side), larger when one lies inside an end disk (stacked).
  double upper = 0.0;
  Vec3 x = Vec3::Zero(), y = Vec3::Zero();
  int iterations = 0;
};

// Straight patches only (Patch::straight).
ConeHullResult cone_hull_distance(const Patch& A, const Patch& B);

// A segment p0 p1 of a meridian half-plane (r, z) revolved about the axis
// through o along unit a.
struct RevolvedSegment {
  Vec3 o, a;
  Vec2 p0, p1;
};

// A lower bound on the distance between the hulls of two revolved segments
// (solid frusta of their end circles, radii |r|): the support bound along
// `dir` (from B towards A) and `steps` more directions, each the difference
// of the last supports (rounding included; <= 0 when the hulls may meet).
double revolved_hull_bound(const RevolvedSegment& A, const RevolvedSegment& B, const Vec3& dir, int steps);

// revolved_hull_bound along one direction for many segment pairs about the
// same two axes (a query's two solids): what depends only on the axes and the
// direction (its components along and across each axis, its offset between
// the origins) is computed once; each pair then costs its four support values
// (about 80 instructions where the whole bound costs about 235). Bit for bit
// the value revolved_hull_bound(A, B, dir, 0) gives.
class RevolvedHullDirection {
 public:
  RevolvedHullDirection(const Vec3& oa, const Vec3& a, const Vec3& ob, const Vec3& b, const Vec3& dir);
  // The bound for A's segment a0 a1 and B's b0 b1 (meridian (r, z)).
  double operator()(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) const;
  // The bound for two patches about these axes (A's and B's o and a): the
  // supports of their revolved arcs or segments, exact (see patch_hull_bound);
  // patch_hull_bound(A, B, dir(), 0), bit for bit.
  double patches(const Patch& A, const Patch& B) const;
  // The direction it was built for (before any rescaling).
  const Vec3& dir() const { return dir_; }
  // No usable direction (zero or not finite): every bound is -inf.
  bool none() const { return none_; }
  // The next direction to try for segments A and B about these axes: the
  // difference of their supports along this one.
  Vec3 next(const RevolvedSegment& A, const RevolvedSegment& B) const;

 private:
  // The bound from the two supports h_A(-u) and h_B(u) - u . d, less the
  // rounding of coordinates up to size and coord.
  double from_supports(double ha, double hb, double size, double coord) const;

  Vec3 dir_, u_, pa_, pb_;
  bool none_ = false;          // no usable direction (zero or not finite): the bound is -inf
  double ua_ = 0, ub_ = 0;     // u . a, u . b
  double na_ = 0, nb_ = 0;     // |u across a|, |u across b|
  double ud_ = 0;              // u . (ob - oa)
  double dmax_ = 0, ocoord_ = 0, l1_ = 0, scale_ = 0;  // |ob - oa|_inf, max |o|_inf, |u|_1, |u| (1 + 4 eps)
};

// A lower bound on the distance between any two patches without iteration:
// the support bound of the two revolved patches along `dir` (from B towards
// A; a query's witness direction suits patches near its contact) and `steps`
// more directions (from the chords' supports). Along a direction with parts
// w_r across and w_z along a patch's axis, the patch's support is the
// maximum over its profile of |r| w_r + z w_z (every azimuth is taken): at a
// segment's end, or at the arc's point of normal w when that lies on the arc
// (its circle's support), else at an end. Exact for the revolved patches'
// hulls, so two convex sides facing each other (a cone or a torus's outer
// band) are bounded by their distance along their common normal; <= 0 when
// the hulls may meet.
double patch_hull_bound(const Patch& A, const Patch& B, const Vec3& dir, int steps);

}  // namespace revdist
