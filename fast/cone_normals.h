// Normal lines of conical patches (cones, cylinders, flat annuli: segments of
// the profile rotated about the axis) against circles and against other cones.
// The conical counterparts of the circle binormals of paper section 3.2: with
// them every critical pair of a patch pair with a straight side is a root of a
// small polynomial, as for two toroidal patches.
#pragma once
#include <cstdint>

#include "core/circle3.h"
#include "fast/patch.h"

namespace revdist {

// Output capacities, proven by the degree argument in cone_normals.cpp: no
// candidate of circle_cone_critical is ever dropped; cone_cone_normals keeps
// every pair of the generic (at most 4 common normals) case and, when a
// near-degenerate system has more candidates than this, keeps the first ones,
// sets *degenerate (callers then do not trust the pair as separated) and
// counts it in cone_normals_fallbacks().
constexpr int kCircleConeCriticalMax = 32;
constexpr int kConeConeNormalsMax = 64;

// Calls of cone_cone_normals that had more candidate pairs than
// kConeConeNormalsMax (process-wide, all threads).
std::uint64_t cone_normals_fallbacks();

// Points of circle C (world) that are critical points of the signed distance to
// the whole cone line of straight patch K, h(P) = n . (rho_K(P), z_K(P)) - off:
// the roots of d h / d theta, squared into a degree-8 polynomial in tan(theta/2)
// (its roots include the points where C crosses K's axis). Writes at most
// kCircleConeCriticalMax points to out (duplicates possible where the two root
// charts meet) and returns their count. *degenerate is set when h is constant
// on C (C coaxial with K and h flat): then out holds the points where rho_K is
// extreme or equals the radius of one of K's end points, the ends of the arcs of
// C whose feet fall inside the segment.
int circle_cone_critical(const Circle3& C, const Patch& K, Vec3* out, bool* degenerate);

// Common normal lines of the whole cones of straight patches A and B that meet
// B's axis within the height range of B's segment's normals (plus a margin): the
// lines meeting both axes at the cones' normal angles. Writes pairs (x on A's
// cone, y on B's cone; either NaN where the line meets that cone only at r < 0)
// and returns their count (at most kConeConeNormalsMax). Roots come from the resultant (a
// quartic), from the closed form for two cylinders (the common perpendicular of
// the axes), or, when the resultant vanishes to rounding (nearly parallel
// axes), from Newton on a grid of starts; all are polished on the unsquared
// conditions. Flat annuli and exactly parallel axes admit only families of such
// lines, along which the distance is constant or monotone, so their extremes
// are at the patch boundaries: those cases return 0. *degenerate is set only
// when candidates exceeded the capacity (see kConeConeNormalsMax).
int cone_cone_normals(const Patch& A, const Patch& B, Vec3* x_out, Vec3* y_out, bool* degenerate);

// Points where the line through p with direction d meets patch P's whole
// surface of revolution (torus or cone), within |s| <= s_max of p. Returns the
// count (at most 4).
int line_surface_intersections(const Vec3& p, const Vec3& d, double s_max, const Patch& P, Vec3* out);

// Points where circle C meets patch P's whole surface of revolution (torus or
// cone): roots of a polynomial of degree 8 (torus) or 4 (cone) in tan(θ/2).
// Returns the count (at most 18: two root charts of degree <= 8, see
// cone_normals.cpp; a buffer of kCircleConeCriticalMax holds it). None when C
// lies on the surface.
int circle_surface_intersections(const Circle3& C, const Patch& P, Vec3* out);

}  // namespace revdist
