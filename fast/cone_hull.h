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

// A lower bound on the distance between any two patches without iteration to
// convergence: every point of a toroidal patch of at most a half turn lies
// within its arc's sagitta of its chord's cone, at the same azimuth, so both
// patches lie within their sagittas of their end circles' hulls (solid
// frusta), and the support bound along any direction holds for the hulls
// (see cone_hull_distance). The directions tried: `dir` (from B towards A;
// a query's witness direction suits patches near its contact) and `steps`
// more, each the difference of the last supports. -inf when an arc turns
// more than a half turn; <= 0 or negative when the hulls may meet.
double patch_hull_bound(const Patch& A, const Patch& B, const Vec3& dir, int steps);

}  // namespace revdist
