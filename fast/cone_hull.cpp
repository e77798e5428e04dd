// Distance between the convex hulls of two conical patches (see the header).
//
// A conical patch is the segment p0 p1 (r >= 0) rotated about the axis; each
// generator point is a convex combination of the end circles' points at its
// azimuth, so the patch lies in F = conv(E0 u E1), a solid frustum, whose
// support function is h_F(u) = max_i (u . c_i + r_i |u - (u . a) a|). For any
// u != 0 every x in A has u . x >= -h_A(-u) and every y in B has
// u . y <= h_B(u), so
//   |x - y| >= (-h_A(-u) - h_B(u)) / |u|,
// with equality at the direction between the hulls' closest points (convex
// duality). No normal line is solved for, so nearly parallel axes cost
// nothing in conditioning: the bound depends on u only to second order where
// the supports are smooth and first order at a kink, and u comes from
// Gilbert's iteration on the Minkowski difference A - B (support points of
// the frusta, closest point of a simplex of at most 4 of them), whose
// correctness the bound does not rely on: any direction gives a valid bound.
#include "fast/cone_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace revdist {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Frustum {
  Vec3 c[2];  // end circle centres, relative to the shared origin
  double r[2];
  Vec3 a;
};

Frustum frustum(const Patch& P, const Vec3& shift) {
  Frustum f;
  f.c[0] = (P.o - shift) + P.p0.y() * P.a;
  f.c[1] = (P.o - shift) + P.p1.y() * P.a;
  f.r[0] = P.p0.x();
  f.r[1] = P.p1.x();
  f.a = P.a;
  return f;
}

// Support value of F in direction u, and the supporting point when p is given.
double support(const Frustum& f, const Vec3& u, Vec3* p = nullptr) {
  const Vec3 up = u - u.dot(f.a) * f.a;
  const double n = up.norm();
  Vec3 e = n > 0 ? Vec3(up / n) : Vec3::Zero();  // any rim point supports when u is along the axis
  const double h0 = u.dot(f.c[0]) + f.r[0] * n, h1 = u.dot(f.c[1]) + f.r[1] * n;
  const int i = h0 >= h1 ? 0 : 1;
  if (p) *p = f.c[i] + f.r[i] * e;
  return i == 0 ? h0 : h1;
}

struct Vert {
  Vec3 w, pa, pb;  // w = pa - pb
};

// Closest point to the origin of the convex hull of s[0..n): the projection
// onto the affine hull of the subset whose barycentric weights are all
// positive and whose point is nearest (the closest point lies in the relative
// interior of some face, where it is that face's projection). Writes the
// weights, reduces s to that subset and returns the point.
Vec3 closest_in_simplex(Vert* s, int* n, double* lam) {
  double best = std::numeric_limits<double>::infinity();
  Vert keep[4];
  double keep_l[4];
  int keep_n = 0;
  Vec3 best_v = Vec3::Zero();
  // Only faces holding the newest vertex s[n - 1]: the previous simplex's
  // closest point was v, and the new support point lies beyond it along -v,
  // so the new closest point's face holds it (Gilbert's iteration; in
  // rounding a face without it only stops the iteration early, and any
  // direction gives a valid bound).
  const int newest = 1 << (*n - 1);
  for (int mask = 1; mask < (1 << *n); ++mask) {
    if (!(mask & newest)) continue;
    int idx[4], k = 0;
    for (int i = 0; i < *n; ++i)
      if (mask & (1 << i)) idx[k++] = i;
    double l[4] = {1, 0, 0, 0};
    if (k > 1) {
      // Gram system for mu_j (j = 1..k-1): sum_l G_jl mu_l = -(P_j - P_0) . P_0.
      const Vec3& p0 = s[idx[0]].w;
      Vec3 e[3];
      double g[3][4];
      const int m = k - 1;
      for (int j = 0; j < m; ++j) e[j] = s[idx[j + 1]].w - p0;
      double diag = 1;
      for (int j = 0; j < m; ++j) {
        for (int q = 0; q < m; ++q) g[j][q] = e[j].dot(e[q]);
        g[j][m] = -e[j].dot(p0);
        diag *= g[j][j];
      }
      // Gaussian elimination with partial pivoting; a nearly flat face is skipped.
      bool ok = diag > 0;
      for (int col = 0; ok && col < m; ++col) {
        int piv = col;
        for (int r = col + 1; r < m; ++r)
          if (std::abs(g[r][col]) > std::abs(g[piv][col])) piv = r;
        if (!(std::abs(g[piv][col]) > 0)) ok = false;
        for (int q = 0; ok && q <= m; ++q) std::swap(g[col][q], g[piv][q]);
        for (int r = col + 1; ok && r < m; ++r) {
          const double f = g[r][col] / g[col][col];
          for (int q = col; q <= m; ++q) g[r][q] -= f * g[col][q];
        }
      }
      if (ok) {
        double det = 1;
        for (int j = 0; j < m; ++j) det *= g[j][j];
        ok = std::abs(det) > 1e-12 * diag;
      }
      if (!ok) continue;
      double mu[3];
      for (int j = m - 1; j >= 0; --j) {
        double t = g[j][m];
        for (int q = j + 1; q < m; ++q) t -= g[j][q] * mu[q];
        mu[j] = t / g[j][j];
      }
      l[0] = 1;
      for (int j = 0; j < m; ++j) l[0] -= (l[j + 1] = mu[j]);
      bool inside = true;
      for (int j = 0; j < k; ++j) inside = inside && l[j] > 0;
      if (!inside) continue;
    }
    Vec3 v = Vec3::Zero();
    for (int j = 0; j < k; ++j) v += l[j] * s[idx[j]].w;
    const double d = v.squaredNorm();
    if (d < best) {
      best = d;
      best_v = v;
      keep_n = k;
      for (int j = 0; j < k; ++j) keep[j] = s[idx[j]], keep_l[j] = l[j];
    }
  }
  for (int j = 0; j < keep_n; ++j) s[j] = keep[j], lam[j] = keep_l[j];
  *n = keep_n;
  return best_v;
}

// The point of straight patch P nearest to x in x's meridian plane of P.
Vec3 onto_patch(const Patch& P, const Vec3& x) {
  Vec3 er;
  const Vec2 q = patch_local(P, x, &er);
  const Vec2 d = P.p1 - P.p0;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((q - P.p0).dot(d) / l2, 0.0, 1.0) : 0.0;
  return patch_world(P, P.p0 + t * d, er);
}

}  // namespace

ConeHullResult cone_hull_distance(const Patch& A, const Patch& B) {
  ConeHullResult res;
  res.lower = -std::numeric_limits<double>::infinity();
  const Vec3 shift = A.o + 0.5 * (A.p0.y() + A.p1.y()) * A.a;
  const Frustum fa = frustum(A, shift), fb = frustum(B, shift);
  double size = 0;
  for (const Frustum* f : {&fa, &fb})
    for (int i = 0; i < 2; ++i) size = std::max(size, f->c[i].cwiseAbs().maxCoeff() + f->r[i]);

  Vert s[4];
  int n = 0;
  double lam[4] = {1, 0, 0, 0};
  Vec3 v = 0.5 * (fa.c[0] + fa.c[1]) - 0.5 * (fb.c[0] + fb.c[1]);
  if (!(v.squaredNorm() > 0)) v = Vec3::UnitX();
  double vlen = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 64; ++it) {
    res.iterations = it + 1;
    Vert w;
    support(fa, -v, &w.pa);
    support(fb, v, &w.pb);
    w.w = w.pa - w.pb;
    // |v| - v . w / |v| is the gap between the current point and the bound along v.
    const double vn = v.norm();
    if (n > 0 && vn - v.dot(w.w) / vn <= 4 * kEps * size) break;
    bool dup = false;
    for (int i = 0; i < n; ++i) dup = dup || s[i].w == w.w;
    if (dup) break;
    s[n++] = w;
    const Vec3 next = closest_in_simplex(s, &n, lam);
    const double nl = next.norm();
    if (!(nl > 0)) return res;  // the hulls meet (or touch): no bound
    if (!(nl < vlen)) break;    // no progress: rounding has the last word
    v = next;
    vlen = nl;
    if (n == 4) return res;  // a tetrahedron around a point that is not the origin: cannot be closest
  }
  // The bound along u (not normalised; divided by |u| below). v is the
  // difference of two hull points, each rounded to ulps of the frusta's
  // extent S, so its direction is off by ~eps S / |v|; where a support ties
  // both end circles (the closest point inside a generator: cans side by
  // side) that costs the bound first order, S eps S / |v|. Every direction
  // gives a valid bound, so v is also tried with its component along each
  // axis set so that it is normal to that cone's generator at the support,
  // which removes that first-order term; the best candidate is kept.
  auto gap_along = [&](const Vec3& d) { return (-support(fa, -d) - support(fb, d)) / d.norm(); };
  // The generator at the support of f in direction s * d is normal to d when
  // d . a = -s |d_perp| t_r / t_z ((t_r, t_z) the segment's direction).
  auto normal_to = [](const Patch& P, const Vec3& d, double s) {
    const Vec2 t = P.p1 - P.p0;
    if (!(std::abs(t.y()) > 0)) return d;
    const Vec3 dp = d - d.dot(P.a) * P.a;
    return Vec3(dp - s * dp.norm() * t.x() / t.y() * P.a);
  };
  // The hulls' closest points, moved onto the patches: an upper bound, and
  // their difference another direction (the simplex's v loses digits to
  // cancellation when the simplex is long and thin).
  Vec3 x = Vec3::Zero(), y = Vec3::Zero();
  for (int j = 0; j < n; ++j) x += lam[j] * s[j].pa, y += lam[j] * s[j].pb;
  res.x = onto_patch(A, x + shift);
  res.y = onto_patch(B, y + shift);
  res.upper = (res.x - res.y).norm();
  Vec3 u = v;
  double best = gap_along(u);
  // Normal to both generators at once (closest points inside both, as for
  // crossing cans): Newton in the span of the two axes on
  // h_P(d) = d . a_P + s_P |d_perp,P| t_r / t_z = 0; alternating the single
  // corrections above converges only at rate cos^2 of the axes' angle.
  auto normal_to_both = [&](Vec3 d) {
    const Vec2 ta = A.p1 - A.p0, tb = B.p1 - B.p0;
    if (!(std::abs(ta.y()) > 0 && std::abs(tb.y()) > 0)) return d;
    const double ka = -ta.x() / ta.y(), kb = tb.x() / tb.y();  // h_A = d.a_A - ka |..|, h_B = d.a_B - kb |..|
    for (int it = 0; it < 3; ++it) {
      const Vec3 pa = d - d.dot(A.a) * A.a, pb = d - d.dot(B.a) * B.a;
      const double la = pa.norm(), lb = pb.norm();
      if (!(la > 0 && lb > 0)) return d;
      const double fa_ = d.dot(A.a) + ka * la, fb_ = d.dot(B.a) + kb * lb;
      // d + al a_A + be b_B: derivatives of h_A, h_B in al and be.
      const double c = A.a.dot(B.a);
      const double j11 = 1, j12 = c + ka * pa.dot(B.a) / la;
      const double j21 = c + kb * pb.dot(A.a) / lb, j22 = 1;
      const double det = j11 * j22 - j12 * j21;
      if (!(std::abs(det) > 1e-300)) return d;
      const double al = -(fa_ * j22 - fb_ * j12) / det, be = -(j11 * fb_ - j21 * fa_) / det;
      d += al * A.a + be * B.a;
    }
    return d;
  };
  // The cones' normals at the witnesses: their azimuths err by the
  // witnesses' tangential error over the radius, not over the gap.
  auto cone_normal = [](const Patch& P, const Vec3& p) {
    Vec3 er;
    patch_local(P, p, &er);
    return Vec3(P.n.x() * er + P.n.y() * P.a);
  };
  const Vec3 na = cone_normal(A, res.x), nb = cone_normal(B, res.y);
  for (const Vec3& base : {v, Vec3(res.x - res.y), na, Vec3(-na), nb, Vec3(-nb)})
    for (const Vec3& c : {base, normal_to(A, base, -1), normal_to(B, base, 1), normal_to(B, normal_to(A, base, -1), 1),
                          normal_to(A, normal_to(B, base, 1), -1), normal_to_both(base)}) {
      if (!(c.squaredNorm() > 0)) continue;
      const double gc = gap_along(c);
      if (gc > best) best = gc, u = c;
    }
  const double g = -support(fa, -u) - support(fb, u);
  // Rounding: each support value is a dot product and a norm of terms of at
  // most |u|_1 (|c| + r); the centres themselves are the patch's to a few
  // ulps of its coordinates (shift and axis origin). 32 eps of those covers it.
  const double coord = std::max({A.o.cwiseAbs().maxCoeff(), B.o.cwiseAbs().maxCoeff(), shift.cwiseAbs().maxCoeff(),
                                 std::abs(A.p0.y()), std::abs(A.p1.y()), std::abs(B.p0.y()), std::abs(B.p1.y())});
  const double err = 32 * kEps * u.lpNorm<1>() * (size + coord);
  const double ulen = u.norm() * (1 + 4 * kEps);
  res.lower = (g - err) / ulen;
  if (res.lower > 0) res.lower *= 1 - 4 * kEps;
  return res;
}

RevolvedHullDirection::RevolvedHullDirection(const Vec3& oa, const Vec3& a, const Vec3& ob, const Vec3& b,
                                             const Vec3& dir)
    : dir_(dir), u_(dir) {
  // A direction from a pair of points 1e-160 apart would square into the
  // subnormals, where |u| keeps a few digits: such a u (or a huge one) is
  // first scaled by a power of two (exact: the bound is the same for any
  // positive multiple of u).
  double uu = u_.squaredNorm();
  if (!(uu >= 0x1p-800 && uu <= 0x1p800)) {
    const double m = u_.cwiseAbs().maxCoeff();
    if (!(m > 0) || !std::isfinite(m)) {
      none_ = true;
      return;
    }
    int e = 0;
    std::frexp(m, &e);
    u_ = Vec3(std::ldexp(u_.x(), -e), std::ldexp(u_.y(), -e), std::ldexp(u_.z(), -e));
    uu = u_.squaredNorm();
  }
  // In coordinates from A's axis origin: A's end circles have centres z a
  // and radii |r|, B's centres d + z b, d = ob - oa.
  const Vec3 d = ob - oa;
  ua_ = u_.dot(a), ub_ = u_.dot(b);
  // |u_perp| from the vector, not sqrt(uu - ua^2): along an axis (flat
  // faces facing each other) that difference cancels to sqrt(eps) |u|,
  // which the radius multiplies (a stress near_parallel_planes case put
  // the bound 1.9e-10 above the distance).
  pa_ = u_ - ua_ * a, pb_ = u_ - ub_ * b;
  na_ = pa_.norm(), nb_ = pb_.norm();
  ud_ = u_.dot(d);
  dmax_ = d.cwiseAbs().maxCoeff();
  ocoord_ = std::max(oa.cwiseAbs().maxCoeff(), ob.cwiseAbs().maxCoeff());
  l1_ = u_.lpNorm<1>();
  scale_ = std::sqrt(uu) * (1 + 4 * kEps);
}

double RevolvedHullDirection::operator()(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) const {
  if (none_) return -std::numeric_limits<double>::infinity();
  const double za[2] = {a0.y(), a1.y()}, ra[2] = {std::abs(a0.x()), std::abs(a1.x())};
  const double zb[2] = {b0.y(), b1.y()}, rb[2] = {std::abs(b0.x()), std::abs(b1.x())};
  // Rounding as in cone_hull_distance: 32 eps |u|_1 (size + coord), size the
  // largest |centre| + r (centres from A's origin), coord the inputs'.
  const double size = std::max({std::abs(za[0]) + ra[0], std::abs(za[1]) + ra[1], dmax_ + std::abs(zb[0]) + rb[0],
                                dmax_ + std::abs(zb[1]) + rb[1]});
  const double coord =
      std::max({ocoord_, std::abs(za[0]), std::abs(za[1]), std::abs(zb[0]), std::abs(zb[1])});
  // h_A(-u) = max_i (-u . c_i + r_i |u_perp|), h_B(u) = u . d + max_j (u . b z_j + r_j |u_perp|).
  const double ha = std::max(-ua_ * za[0] + ra[0] * na_, -ua_ * za[1] + ra[1] * na_);
  const double hb = std::max(ub_ * zb[0] + rb[0] * nb_, ub_ * zb[1] + rb[1] * nb_);
  return from_supports(ha, hb, size, coord);
}

double RevolvedHullDirection::from_supports(double ha, double hb, double size, double coord) const {
  const double g = -ha - ud_ - hb;
  const double err = 32 * kEps * l1_ * (size + coord);
  return (g - err) / scale_;
}

Vec3 RevolvedHullDirection::next(const RevolvedSegment& A, const RevolvedSegment& B) const {
  // The support points' difference (a step of Gilbert's iteration without
  // its simplex). Any rim point supports along an axis.
  const double za[2] = {A.p0.y(), A.p1.y()}, ra[2] = {std::abs(A.p0.x()), std::abs(A.p1.x())};
  const double zb[2] = {B.p0.y(), B.p1.y()}, rb[2] = {std::abs(B.p0.x()), std::abs(B.p1.x())};
  const int ia = -ua_ * za[0] + ra[0] * na_ >= -ua_ * za[1] + ra[1] * na_ ? 0 : 1;
  const int ib = ub_ * zb[0] + rb[0] * nb_ >= ub_ * zb[1] + rb[1] * nb_ ? 0 : 1;
  const Vec3 ea = na_ > 0 ? Vec3(-pa_ / na_) : Vec3::Zero();
  const Vec3 eb = nb_ > 0 ? Vec3(pb_ / nb_) : Vec3::Zero();
  return (za[ia] * A.a + ra[ia] * ea) - (B.o - A.o + zb[ib] * B.a + rb[ib] * eb);
}

namespace {

// The best of a bound along `dir` and `steps` more directions, each from
// the last one's supports of the segments A and B.
template <class Bound>
double stepped(const RevolvedSegment& A, const RevolvedSegment& B, const Vec3& dir, int steps, Bound bound) {
  double best = -std::numeric_limits<double>::infinity();
  Vec3 u = dir;
  for (int k = 0; k <= steps; ++k) {
    const RevolvedHullDirection h(A.o, A.a, B.o, B.a, u);
    if (h.none()) break;
    best = std::max(best, bound(h));
    if (k == steps) break;
    u = h.next(A, B);
  }
  return best;
}

}  // namespace

double revolved_hull_bound(const RevolvedSegment& A, const RevolvedSegment& B, const Vec3& dir, int steps) {
  return stepped(A, B, dir, steps, [&](const RevolvedHullDirection& h) { return h(A.p0, A.p1, B.p0, B.p1); });
}

namespace {

// max over the arc's points q of w . q: the circle's support c . w + rho |w|
// when w's direction falls within the arc's (taken when in doubt: larger),
// else the better end. Arcs of more than a half turn take the circle's.
double arc_support(const Patch& P, const Vec2& w) {
  double h = std::max(P.p0.dot(w), P.p1.dot(w));
  const Vec2 v0 = P.p0 - P.c, v1 = P.p1 - P.c;
  auto cross = [](const Vec2& x, const Vec2& y) { return x.x() * y.y() - x.y() * y.x(); };
  const double s = P.sweep >= 0 ? 1.0 : -1.0, wn = w.norm();
  const double slack = 1e-9 * wn * P.rho;
  const bool inside =
      !(std::abs(P.sweep) <= M_PI) || (s * cross(v0, w) >= -slack && s * cross(w, v1) >= -slack);
  if (inside) h = std::max(h, P.c.dot(w) + P.rho * wn);
  return h;
}

// max over the patch's points of (r wr + z wz), wr >= 0, for its profile
// points q = (r, z): the support of the revolved patch along a direction whose
// parts across and along the axis are wr and wz (every azimuth is taken; see
// revolved_hull_bound). A segment's ends hold the maximum, an arc's its
// support. (A patch's ends have r >= 0, and a point of an arc dipping past the
// axis stands for its point on the axis (patch_point): such points lie
// between two where the arc crosses the axis, at z between theirs, so those
// hold their supports.)
double profile_support(const Patch& P, double wr, double wz) {
  if (P.straight) return std::max(P.p0.x() * wr + P.p0.y() * wz, P.p1.x() * wr + P.p1.y() * wz);
  return arc_support(P, Vec2(wr, wz));
}

// The largest |z| + |r| of a patch's profile (its circle's for an arc).
double profile_size(const Patch& P) {
  double s = std::max(std::abs(P.p0.y()) + std::abs(P.p0.x()), std::abs(P.p1.y()) + std::abs(P.p1.x()));
  if (!P.straight) s = std::max(s, std::abs(P.c.y()) + std::abs(P.c.x()) + P.rho);
  return s;
}

}  // namespace

double RevolvedHullDirection::patches(const Patch& A, const Patch& B) const {
  if (none_) return -std::numeric_limits<double>::infinity();
  // h_A(-u) and h_B(u) - u . d as in operator(), with the arcs' own supports
  // (exact: a chord cone's hull less the arc's sagitta, this bound's first
  // form, lost up to twice the sagitta).
  const double ha = profile_support(A, na_, -ua_), hb = profile_support(B, nb_, ub_);
  const double sa = profile_size(A), sb = profile_size(B);
  return from_supports(ha, hb, std::max(sa, dmax_ + sb), std::max(ocoord_, std::max(sa, sb)));
}

double patch_hull_bound(const Patch& A, const Patch& B, const Vec3& dir, int steps) {
  // (The next directions from the chords' supports: any direction bounds.)
  return stepped({A.o, A.a, A.p0, A.p1}, {B.o, B.a, B.p0, B.p1}, dir, steps,
                 [&](const RevolvedHullDirection& h) { return h.patches(A, B); });
}

}  // namespace revdist
