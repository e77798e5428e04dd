// A patch of a solid's surface: one arc or segment of its biarc tree rotated
// about the solid's axis (paper section 3): a toroidal patch (arc; a sphere zone
// when the arc's centre is on the axis, a spindle patch when it is beyond it) or
// a conical one (segment: cone, cylinder or flat annulus). World frame.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/arc2.h"
#include "core/circle3.h"
#include "core/vec.h"

namespace revdist {

struct Patch {
  Vec3 o = Vec3::Zero();  // axis origin: world position of local (r, z) = (0, 0)
  Vec3 a = Vec3::UnitZ(); // unit axis direction
  bool straight = false;  // segment (cone) or arc (torus)
  Vec2 p0 = Vec2::Zero(), p1 = Vec2::Zero();  // local (r, z) end points, r >= 0
  // arc: centre c (c.r < 0 for a spindle, 0 for a sphere), radius rho, unit
  // direction d0 from c to p0, signed sweep (> 0 counter-clockwise in (r, z)).
  Vec2 c = Vec2::Zero();
  double rho = 0.0;
  Vec2 d0 = Vec2(1, 0);
  double sweep = 0.0;
  // segment: unit normal n and offset with n . q = off on the line.
  Vec2 n = Vec2(0, 1);
  double off = 0.0;
};

// The patch of `arc` (solid-local (r, z)) for a solid whose local frame maps to
// the world by x = R * local + t. Straight arcs (curvature 0) give cones.
Patch make_patch(const Arc2& arc, const Mat3& R, const Vec3& t);

// Local (rho, z) of a world point, and the unit radial direction of its
// meridian half-plane (any unit vector normal to the axis when x is on it).
// (Inline: the local proofs call it once a box.)
inline Vec2 patch_local(const Patch& p, const Vec3& x, Vec3* e_r = nullptr) {
  const Vec3 d = x - p.o;
  const double z = d.dot(p.a);
  const Vec3 h = d - z * p.a;
  const double r = h.norm();
  if (e_r) {
    if (r > 0) {
      *e_r = h / r;
    } else {
      // On the axis: every half-plane contains x; pick one.
      const Vec3 any = std::abs(p.a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      *e_r = p.a.cross(any).normalized();
    }
  }
  return Vec2(r, z);
}
Vec3 patch_world(const Patch& p, const Vec2& q, const Vec3& e_r);

// The circle swept by the arc's centre (radius |c.r|; a point for a sphere).
// (This and the small functions below are inline: the kernels call them per
// arc pair.)
inline Circle3 patch_major_circle(const Patch& p) { return {p.o + p.c.y() * p.a, p.a, std::abs(p.c.x())}; }
// The circle swept by end point i (0 or 1); radius 0 at a pole.
inline Circle3 patch_end_circle(const Patch& p, int i) {
  const Vec2& q = i == 0 ? p.p0 : p.p1;
  return {p.o + q.y() * p.a, p.a, std::max(0.0, q.x())};
}

// Is local point q on the patch's arc or segment: within tol of its circle or
// line, and inside its angular or parameter range?
bool patch_contains_local(const Patch& p, const Vec2& q, double tol);

// The signed function of the patch's whole surface of revolution (the full
// torus or cone it lies on): |q - c| - rho for an arc, n . q - off for a segment.
double patch_surface_function(const Patch& p, const Vec2& q);

// A disk in (r, z) holding the patch's arc or segment (centre, radius): the
// chord's midpoint and half chord for arcs up to a half turn, the arc's circle
// beyond. Rotated, a solid torus around a circle holding the whole patch.
inline void patch_disk(const Patch& p, Vec2* centre, double* radius) {
  if (!p.straight && std::abs(p.sweep) > M_PI) {
    *centre = p.c;
    *radius = p.rho;
    return;
  }
  *centre = 0.5 * (p.p0 + p.p1);
  *radius = 0.5 * (p.p1 - p.p0).norm();
}
// The circle that disk's centre sweeps (world).
inline Circle3 patch_disk_circle(const Patch& p, const Vec2& centre) {
  return {p.o + centre.y() * p.a, p.a, std::max(centre.x(), 0.0)};
}

// The length of the patch's arc or segment (in (r, z)).
inline double patch_profile_length(const Patch& p) {
  return p.straight ? (p.p1 - p.p0).norm() : p.rho * std::abs(p.sweep);
}
// At least the patch's largest distance from its axis (an arc's: its ends' or
// its circle's).
inline double patch_max_radius(const Patch& p) {
  return std::max({p.p0.x(), p.p1.x(), p.straight ? 0.0 : p.c.x() + p.rho, 0.0});
}

// Radius of a ball around the patch's axis point at the patch's mean height that
// holds the whole patch (used for root-finding ranges and quick rejection).
double patch_extent(const Patch& p, Vec3* centre);

}  // namespace revdist
