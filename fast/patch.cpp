// Patches of revolution: construction from biarc arcs, local/world maps and
// membership tests (paper section 3).
#include "fast/patch.h"

#include <algorithm>
#include <cmath>

namespace revdist {

Patch make_patch(const Arc2& arc, const Mat3& R, const Vec3& t) {
  Patch p;
  p.o = t;
  p.a = R.col(2).normalized();
  p.p0 = arc.start;
  p.p1 = arc.end();
  if (arc.straight()) {
    p.straight = true;
    const Vec2 d = (p.p1 - p.p0);
    const double len = d.norm();
    p.n = len > 0 ? Vec2(-d.y() / len, d.x() / len) : Vec2(-arc.tangent.y(), arc.tangent.x());
    p.off = p.n.dot(p.p0);
  } else {
    p.c = arc.center();
    p.rho = 1.0 / std::abs(arc.curvature);
    const Vec2 v = p.p0 - p.c;
    p.d0 = v / v.norm();
    p.sweep = arc.curvature * arc.length;
  }
  return p;
}

Vec3 patch_world(const Patch& p, const Vec2& q, const Vec3& e_r) { return p.o + q.x() * e_r + q.y() * p.a; }

bool patch_contains_local(const Patch& p, const Vec2& q, double tol) {
  if (!q.allFinite()) return false;
  if (p.straight) {
    if (std::abs(p.n.dot(q) - p.off) > tol) return false;
    const Vec2 d = p.p1 - p.p0;
    const double s = (q - p.p0).dot(d);
    return s >= -tol * d.norm() && s <= d.squaredNorm() + tol * d.norm();
  }
  const Vec2 v = q - p.c;
  const double len = v.norm();
  if (std::abs(len - p.rho) > tol) return false;
  // Angle from d0 to v in the sweep's direction, in [0, 2 pi).
  double phi = std::atan2(cross2(p.d0, v), p.d0.dot(v));
  if (p.sweep < 0) phi = -phi;
  if (phi < 0) phi += 2 * M_PI;
  const double sweep = std::abs(p.sweep);
  const double slack = p.rho > 0 ? tol / p.rho : 0.0;
  return phi <= sweep + slack || phi >= 2 * M_PI - slack;
}

double patch_surface_function(const Patch& p, const Vec2& q) {
  return p.straight ? p.n.dot(q) - p.off : (q - p.c).norm() - p.rho;
}

double patch_extent(const Patch& p, Vec3* centre) {
  // A box of the local ends (and of the arc's extreme points) in (r, z), then
  // the ball around the axis point at mid height through the box's far corner.
  double rmax = std::max(p.p0.x(), p.p1.x());
  double zlo = std::min(p.p0.y(), p.p1.y()), zhi = std::max(p.p0.y(), p.p1.y());
  if (!p.straight) {
    rmax = std::max(rmax, p.c.x() + p.rho);
    zlo = std::min(zlo, p.c.y() - p.rho);
    zhi = std::max(zhi, p.c.y() + p.rho);
  }
  const double zm = 0.5 * (zlo + zhi);
  *centre = p.o + zm * p.a;
  return std::hypot(std::max(rmax, 0.0), 0.5 * (zhi - zlo));
}

}  // namespace revdist
