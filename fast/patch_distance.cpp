// Distance between two patches of revolution by enumeration of critical lines
// (see the header for the argument).
#include "fast/patch_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fast/circle_bound.h"
#include "fast/circle_distance.h"
#include "fast/cone_hull.h"
#include "fast/cone_normals.h"
#include "fast/turn.h"

namespace revdist {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Side {
  const Patch& P;
  Circle3 end[2];
  Circle3 major;  // arcs only
  double tol;     // on-patch tolerance
};

// Candidate points and pairs, and the extremes of each patch's surface
// function over the other patch.
struct Collector {
  const Patch& A;
  const Patch& B;
  double tol;
  double cutoff;       // sub-problems proven at least this far apart are skipped
  bool need_g;         // the sign tests are needed (the bounding tori meet)
  PatchPairResult res;
  // True when a sub-problem's lower bound reaches the cutoff: it is skipped and
  // its bound kept in res.lower_skipped.
  bool skip(double lb) {
    if (need_g || !(lb >= cutoff)) return false;
    res.lower_skipped = std::min(res.lower_skipped, lb);
    return true;
  }
  double gb_min = kInf, gb_max = -kInf;  // g_B over points of A
  double ga_min = kInf, ga_max = -kInf;  // g_A over points of B

  bool on_a(const Vec3& x) const { return patch_contains_local(A, patch_local(A, x), tol); }
  bool on_b(const Vec3& y) const { return patch_contains_local(B, patch_local(B, y), tol); }
  void point_a(const Vec3& x) {
    if (!need_g) return;
    const double g = patch_surface_function(B, patch_local(B, x));
    if (g < gb_min) { gb_min = g; res.a_low = x; }
    if (g > gb_max) { gb_max = g; res.a_high = x; }
  }
  void point_b(const Vec3& y) {
    if (!need_g) return;
    const double g = patch_surface_function(A, patch_local(A, y));
    if (g < ga_min) { ga_min = g; res.b_low = y; }
    if (g > ga_max) { ga_max = g; res.b_high = y; }
  }
  void pair(const Vec3& x, const Vec3& y) {
    const double d = (x - y).norm();
    if (!res.found || d < res.upper) {
      res.found = true;
      res.upper = d;
      res.x = x;
      res.y = y;
    }
  }
};

// The normal lines from world point x to straight patch K's whole cone: in x's
// meridian plane of K the cone is two lines, the generator in x's half-plane and
// its mirror in the opposite one, with one normal line from x to each. For each,
// the foot (on the cone only when its r >= 0) and the unit direction along the
// cone's normal. Returns 2.
struct ConeNormal {
  Vec3 foot;
  bool foot_on_cone;
  Vec3 dir;
};
int cone_normals_from(const Patch& K, const Vec3& x, ConeNormal out[2]) {
  Vec3 er;
  const Vec2 q = patch_local(K, x, &er);
  int k = 0;
  for (double side : {1.0, -1.0}) {
    const Vec3 e = side * er;
    const Vec2 qs(side * q.x(), q.y());
    const Vec2 f = qs - (K.n.dot(qs) - K.off) * K.n;
    out[k++] = {f.x() >= 0 ? patch_world(K, f, e) : x, f.x() >= 0, K.n.x() * e + K.n.y() * K.a};
  }
  return k;
}

// Binormal lines of two circles (point_a on p, point_b on q). When they form a
// continuum (coaxial, Villarceau or meridian circles), the squared distance is
// constant along it (a connected set of critical points of a smooth function),
// and so is every candidate distance built on it; the part of the family inside
// the patches' ranges is either the whole family or ends where a line meets a
// patch boundary, which the boundary candidates hold. So members sampled around
// q stand for the family: each joins a point of q to its nearest and farthest
// points of p.
// max_len finite: only lines shorter than max_len are needed (a pruning
// caller); *dropped_lb then bounds the left-out part of q from below.
std::vector<CircleBinormal> binormal_lines(const Circle3& p, const Circle3& q, double max_len = kInf,
                                           double* dropped_lb = nullptr, const BinormalArcTest* test = nullptr) {
  bool infinite = false;
  double dlb = kInf;
  auto lines = std::isfinite(max_len) || test
                   ? circle3_circle3_binormal_lines_within(p, q, max_len, &infinite, &dlb, test)
                   : circle3_circle3_binormal_lines(p, q, &infinite);
  if (dropped_lb) *dropped_lb = dlb;
  if (!infinite) return lines;
  const Vec3 nq = q.normal.normalized(), np = p.normal.normalized();
  const Vec3 any = std::abs(nq.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = nq.cross(any).normalized(), v = nq.cross(u);
  constexpr int kSamples = 8;
  for (int k = 0; k < kSamples; ++k) {
    const double th = (k + 0.5) * (2 * M_PI / kSamples);
    const Vec3 mq = q.center + q.radius * (std::cos(th) * u + std::sin(th) * v);
    const Vec3 d = mq - p.center;
    Vec3 h = d - d.dot(np) * np;
    const double hn = h.norm();
    h = hn > 0 ? Vec3(h / hn) : Vec3(np.cross(any).normalized());
    for (double side : {1.0, -1.0}) {
      const Vec3 mp = p.center + side * p.radius * h;
      lines.push_back({mp, mq, (mq - mp).norm()});
    }
  }
  return lines;
}

// The Gauss-map restriction of paper section 3.3 for a torus patch T: a line
// normal to T's torus lies in a meridian plane of T and passes through the
// arc's centre c there, so in T's (r, z) half-plane it leaves c in direction
// psi and meets the torus at angles psi and psi + pi; it reaches the patch only
// when one of them is in the arc's angular window. A ball (x, r) of points
// projects into a disk of radius r (the map to (r, z) is 1-Lipschitz), whose
// directions from c are within asin(r / |q - c|) of q's: the ball can hold the
// other end of such a line only if that cone, from q or from its mirror
// image across the axis, meets the double window.
struct GaussWindow {
  const Patch* T;
  Vec2 mid;            // unit direction of the window's middle
  double cos_h, sin_h; // of the window's half-width
};
// (A segment has no window: its callers test the segment's own range. It
// gets the trivial one, without the trig calls.)
GaussWindow gauss_window(const Patch& T) {
  if (T.straight) return {&T, Vec2(1, 0), 1.0, 0.0};
  // One sine and cosine: the half-width is the middle's angle from d0 up to its sign.
  const double ch = std::cos(0.5 * T.sweep), sa = std::sin(0.5 * T.sweep);
  const Vec2 mid(ch * T.d0.x() - sa * T.d0.y(), sa * T.d0.x() + ch * T.d0.y());
  return {&T, mid, ch, std::abs(sa)};
}
bool gauss_keep(const void* ctx, const Vec3& x, double r) {
  const GaussWindow& g = *static_cast<const GaussWindow*>(ctx);
  const Vec2 q = patch_local(*g.T, x);
  const double slack = 1e-9;  // directions: generous against rounding
  // The normal line lies in a whole meridian plane: past T's axis it runs
  // through the opposite half-plane, where a point's (rho, z) is the mirror
  // (-rho, z) of its place on the line. So the ball may hold an end of such
  // a line at q or at its mirror.
  for (const Vec2& qs : {q, Vec2(-q.x(), q.y())}) {
    const Vec2 v = qs - g.T->c;
    const double len = v.norm();
    if (!(len > r * (1 + slack)) || g.cos_h <= 0) return true;
    const double sd = r / len, cd = std::sqrt(std::max(0.0, 1 - sd * sd));
    const double cos_lim = g.cos_h * cd - g.sin_h * sd;  // cos(half + delta)
    if (cos_lim <= slack) return true;                    // the cone spans a right angle or more
    if (std::abs(v.dot(g.mid)) / len >= cos_lim - slack) return true;
  }
  return false;
}

// Lines normal to torus patch T's major circle at m: the line from m along w, and
// the two points m +- rho w of T's whole torus on it.
void torus_points(const Patch& T, const Vec3& m, const Vec3& w, Vec3 out[2]) {
  out[0] = m + T.rho * w;
  out[1] = m - T.rho * w;
}

// Boundary circle E of one patch (`first` = it belongs to A) against the other
// patch's interior.
void boundary_vs_interior(Collector& c, const Circle3& E, bool e_on_a) {
  const Patch& O = e_on_a ? c.B : c.A;  // the other patch
  auto add = [&](const Vec3& e, const Vec3& o) {
    if (e_on_a) c.pair(e, o); else c.pair(o, e);
  };
  auto add_e = [&](const Vec3& e) { if (e_on_a) c.point_a(e); else c.point_b(e); };
  auto on_o = [&](const Vec3& p) { return e_on_a ? c.on_b(p) : c.on_a(p); };
  // Lower bound: E against the solid torus that holds O (its disk's, or for a
  // toroidal patch its own tube around the major circle).
  {
    Vec2 dc;
    double dr;
    patch_disk(O, &dc, &dr);
    // Closed-form bounds first (fast/circle_bound.h): most skips need no more.
    const Circle3 od = patch_disk_circle(O, dc);
    double lb = circle3_circle3_lower_bound(E, od) - dr;
    if (!O.straight) lb = std::max(lb, circle3_circle3_lower_bound(E, patch_major_circle(O)) - O.rho);
    if (c.skip(lb)) return;
    if (!c.need_g) {
      lb = std::max(lb, circle3_circle3_distance_value(E, od) - dr);
      if (!O.straight) lb = std::max(lb, circle3_circle3_distance_value(E, patch_major_circle(O)) - O.rho);
      if (c.skip(lb)) return;
    }
  }
  if (O.straight) {
    Vec3 pts[kCircleConeCriticalMax];
    bool deg = false;
    const int n = circle_cone_critical(E, O, pts, &deg);
    for (int i = 0; i < n; ++i) {
      add_e(pts[i]);
      ConeNormal cn[2];
      const int nf = cone_normals_from(O, pts[i], cn);
      for (int j = 0; j < nf; ++j)
        if (cn[j].foot_on_cone && on_o(cn[j].foot)) add(pts[i], cn[j].foot);
    }
    return;
  }
  // Pruning allowed (the patches are proven apart, so no sign test needs every
  // candidate): only the arcs of E that come within reach of the cutoff and
  // that O's Gauss window can see; lines are enumerated on E (circle b).
  double dropped = kInf;
  const GaussWindow gw = gauss_window(O);
  const BinormalArcTest test{gauss_keep, &gw};
  const auto lines = c.need_g ? binormal_lines(patch_major_circle(O), E)
                              : binormal_lines(patch_major_circle(O), E, c.cutoff + O.rho, &dropped, &test);
  if (dropped < kInf) c.res.lower_skipped = std::min(c.res.lower_skipped, dropped - O.rho);
  for (const auto& l : lines) {
    const Vec3& e = l.point_b;
    add_e(e);
    const Vec3 d = l.point_a - e;
    const double len = d.norm();
    if (!(len > 0)) continue;
    Vec3 ps[2];
    torus_points(O, l.point_a, d / len, ps);
    for (const Vec3& p : ps)
      if (on_o(p)) add(e, p);
  }
}

void interior_vs_interior(Collector& c, double disk_lb) {
  const Patch& A = c.A;
  const Patch& B = c.B;
  if (!A.straight && !B.straight) {
    const double lb = circle3_circle3_distance_value(patch_major_circle(A), patch_major_circle(B)) - A.rho - B.rho;
    if (c.skip(std::max(lb, disk_lb))) return;
    double dropped = kInf;
    const GaussWindow gw = gauss_window(A);
    const BinormalArcTest test{gauss_keep, &gw};
    const auto lines = c.need_g ? binormal_lines(patch_major_circle(A), patch_major_circle(B))
                                : binormal_lines(patch_major_circle(A), patch_major_circle(B), c.cutoff + A.rho + B.rho,
                                                 &dropped, &test);
    if (dropped < kInf) c.res.lower_skipped = std::min(c.res.lower_skipped, dropped - A.rho - B.rho);
    for (const auto& l : lines) {
      const Vec3 d = l.point_b - l.point_a;
      const double len = d.norm();
      if (!(len > 0)) {
        c.res.degenerate = true;  // the major circles meet: the tori overlap there
        continue;
      }
      const Vec3 w = d / len;
      Vec3 xs[2], ys[2];
      torus_points(A, l.point_a, w, xs);
      torus_points(B, l.point_b, w, ys);
      bool xin[2], yin[2];
      for (int i = 0; i < 2; ++i) {
        xin[i] = c.on_a(xs[i]);
        yin[i] = c.on_b(ys[i]);
        if (xin[i]) c.point_a(xs[i]);
        if (yin[i]) c.point_b(ys[i]);
      }
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          if (xin[i] && yin[j]) c.pair(xs[i], ys[j]);
    }
    return;
  }
  if (c.skip(disk_lb)) return;
  if (A.straight && B.straight) {
    Vec3 xs[kConeConeNormalsMax], ys[kConeConeNormalsMax];
    bool deg = false;
    int n = cone_cone_normals(A, B, xs, ys, &deg);
    if (deg) c.res.degenerate = true;
    // NaN feet fail every membership test.
    for (int i = 0; i < n; ++i) {
      const bool yin = c.on_b(ys[i]);
      if (yin) c.point_b(ys[i]);
      if (yin && c.on_a(xs[i])) c.pair(xs[i], ys[i]);
    }
    n = cone_cone_normals(B, A, ys, xs, &deg);
    if (deg) c.res.degenerate = true;
    for (int i = 0; i < n; ++i) {
      const bool xin = c.on_a(xs[i]);
      if (xin) c.point_a(xs[i]);
      if (xin && c.on_b(ys[i])) c.pair(xs[i], ys[i]);
    }
    return;
  }
  // One torus T, one cone K: normals of K through critical points of T's major circle.
  const bool a_is_torus = !A.straight;
  const Patch& T = a_is_torus ? A : B;
  const Patch& K = a_is_torus ? B : A;
  Vec3 ms[kCircleConeCriticalMax];
  bool deg = false;
  const int n = circle_cone_critical(patch_major_circle(T), K, ms, &deg);
  (void)deg;  // h constant on the major circle: the points returned represent it (see cone_normals.h)
  for (int i = 0; i < n; ++i) {
    ConeNormal cn[2];
    const int nf = cone_normals_from(K, ms[i], cn);
    for (int j = 0; j < nf; ++j) {
      const bool foot_in = cn[j].foot_on_cone && (a_is_torus ? c.on_b(cn[j].foot) : c.on_a(cn[j].foot));
      if (foot_in) { if (a_is_torus) c.point_b(cn[j].foot); else c.point_a(cn[j].foot); }
      // The torus points on this normal line: critical points of K's surface
      // function over T (whether or not the line reaches K's patch), and with
      // the foot a critical pair.
      Vec3 ts[2];
      torus_points(T, ms[i], cn[j].dir, ts);
      for (const Vec3& t : ts) {
        const bool t_in = a_is_torus ? c.on_a(t) : c.on_b(t);
        if (!t_in) continue;
        if (a_is_torus) c.point_a(t); else c.point_b(t);
        if (foot_in) { if (a_is_torus) c.pair(t, cn[j].foot); else c.pair(cn[j].foot, t); }
      }
    }
  }
}

// Points where patch P crosses the other patch O's axis or, for a torus O, its
// major circle: there O's surface function is not smooth (a distance to a line
// or a circle), so its extremes over P may sit there.
void nonsmooth_points(Collector& c, bool on_a) {
  const Patch& P = on_a ? c.A : c.B;
  const Patch& O = on_a ? c.B : c.A;
  Vec3 centre;
  const double ext = patch_extent(P, &centre);
  // The axis line of O, from its point nearest to P's centre.
  const Vec3 p = O.o + (centre - O.o).dot(O.a) * O.a;
  Vec3 pts[kCircleConeCriticalMax];  // circle_surface_intersections: 18, line: 4
  // Each crossing is moved onto P's surface (its foot in its meridian
  // half-plane) before the patch test: near P's apex or tangent crossings the
  // solve leaves it off the surface by more than the test's tolerance (1e-9
  // where O's axis passes 8e-7 from a cone's apex), and the cusp of O's
  // function there would be lost. A genuine point of P can only widen the
  // range of O's function over P, never wrongly separate the patches.
  auto add = [&](int n) {
    for (int i = 0; i < n; ++i) {
      Vec3 er;
      Vec2 q = patch_local(P, pts[i], &er);
      if (P.straight) {
        q -= (P.n.dot(q) - P.off) * P.n;
      } else if (const double D = (q - P.c).norm(); D > 0) {
        q = P.c + (P.rho / D) * (q - P.c);
      }
      if (!(q.x() >= 0)) continue;
      const Vec3 x = patch_world(P, q, er);
      if (on_a ? c.on_a(x) : c.on_b(x)) {
        if (on_a) c.point_a(x); else c.point_b(x);
      }
    }
  };
  if (!O.straight) add(circle_surface_intersections(patch_major_circle(O), P, pts));
  if ((p - centre).norm() <= ext) add(line_surface_intersections(p, O.a, 2 * ext, P, pts));
}

}  // namespace

double patch_disk_bound(const Patch& A, const Patch& B) {
  Vec2 ca, cb;
  double ra, rb;
  patch_disk(A, &ca, &ra);
  patch_disk(B, &cb, &rb);
  return circle3_circle3_distance_value(patch_disk_circle(A, ca), patch_disk_circle(B, cb)) - ra - rb;
}

// Lower bound from the plane of flat annulus F (a straight patch with n_r = 0):
// when patch O lies on one side of that plane, its distance to the plane.
// Heights are linear, so over a circle they range over h(centre) +- r |a_F x n|
// (n the circle's axis); over a cone patch they peak on its end circles (linear
// along each generator); over a torus patch they stay within rho of those of
// its major circle. Exact for parallel flat annuli (stacked coins).
double plane_bound(const Patch& F, const Patch& O) {
  const Vec3 axis_perp = F.a - F.a.dot(O.a) * O.a;
  const double slope = axis_perp.norm();
  auto height = [&](const Vec3& x) { return (x - F.o).dot(F.a) - F.p0.y(); };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto circle_range = [&](const Circle3& c, double pad) {
    const double h = height(c.center);
    lo = std::min(lo, h - c.radius * slope - pad);
    hi = std::max(hi, h + c.radius * slope + pad);
  };
  if (O.straight) {
    circle_range(patch_end_circle(O, 0), 0.0);
    circle_range(patch_end_circle(O, 1), 0.0);
  } else {
    circle_range(patch_major_circle(O), O.rho);
  }
  if (lo > 0) return lo;
  if (hi < 0) return -hi;
  return -std::numeric_limits<double>::infinity();
}

PatchQuick patch_pair_quick(const Patch& A, const Patch& B, const QuickGoal* goal) {
  PatchQuick q;
  q.lower = -std::numeric_limits<double>::infinity();
  if (A.straight && A.n.x() == 0) q.lower = std::max(q.lower, plane_bound(A, B));
  if (B.straight && B.n.x() == 0) q.lower = std::max(q.lower, plane_bound(B, A));
  Vec2 ca, cb;
  double ra, rb;
  patch_disk(A, &ca, &ra);
  patch_disk(B, &cb, &rb);
  const Circle3 da = patch_disk_circle(A, ca), db = patch_disk_circle(B, cb);
  if (goal && (q.lower >= goal->need || circle3_circle3_upper_bound(da, db, goal->hint) - ra - rb < goal->need)) {
    q.complete = false;
    q.lower = std::max(q.lower, circle3_circle3_lower_bound(da, db) - ra - rb);
  } else {
    q.lower = std::max(q.lower, circle3_circle3_distance_value(da, db) - ra - rb);
  }
  if (A.straight || B.straight || (goal && q.lower >= goal->need)) return q;
  const Circle3 ma = patch_major_circle(A), mb = patch_major_circle(B);
  if (goal) {
    // The major circles' solve matters when their gap can reach the goal, or
    // when their closest pair may fall in both windows (the exact case). A
    // pair of their points from the hint stands in for both: closer than the
    // goal, with its tube points a chord or more outside either window, the
    // solve is skipped. (The window test is a guess: at worst a pair the
    // solve would have settled exactly goes on to the caller's proofs.)
    Vec3 pa, pb;
    const double d = circle3_circle3_upper_bound(ma, mb, goal->hint, 3, &pa, &pb);
    if (d - A.rho - B.rho < goal->need) {
      const Vec3 w = d > 0 ? Vec3((pb - pa) / d) : Vec3::Zero();
      if (!patch_contains_local(A, patch_local(A, pa + A.rho * w), (A.p1 - A.p0).norm()) ||
          !patch_contains_local(B, patch_local(B, pb - B.rho * w), (B.p1 - B.p0).norm())) {
        q.complete = false;
        return q;
      }
    }
  }
  const Circle3Circle3Result m = circle3_circle3_distance(ma, mb);
  const double gap = m.distance - A.rho - B.rho;
  q.lower = std::max(q.lower, gap);
  if (!(gap > 0)) return q;
  const Vec3 w = (m.point_b - m.point_a) / m.distance;
  const Vec3 x = m.point_a + A.rho * w, y = m.point_b - B.rho * w;
  Vec3 centre_a, centre_b;
  const double scale = std::max({patch_extent(A, &centre_a), patch_extent(B, &centre_b), m.distance});
  const double tol = 1e-9 * scale + 64 * std::numeric_limits<double>::epsilon() *
                                        std::max(centre_a.cwiseAbs().maxCoeff(), centre_b.cwiseAbs().maxCoeff());
  if (patch_contains_local(A, patch_local(A, x), tol) && patch_contains_local(B, patch_local(B, y), tol)) {
    q.exact = true;
    q.x = x;
    q.y = y;
  }
  return q;
}

namespace {

// The point of patch P's arc or segment at profile fraction u in [0, 1]
// (local (r, z), r not clamped to the axis) and, when qu is given, its
// derivative in u.
// ca, sa: the cosine and sine of the arc's angle u * sweep (unused for a
// segment), for callers that carry them.
Vec2 meridian_point(const Patch& P, double u, double ca, double sa, Vec2* qu) {
  if (P.straight) {
    if (qu) *qu = P.p1 - P.p0;
    return P.p0 + u * (P.p1 - P.p0);
  }
  const Vec2 dir(ca * P.d0.x() - sa * P.d0.y(), sa * P.d0.x() + ca * P.d0.y());
  if (qu) *qu = P.rho * P.sweep * Vec2(-dir.y(), dir.x());
  return P.c + P.rho * dir;
}
Vec2 meridian_point(const Patch& P, double u, Vec2* qu = nullptr) {
  if (P.straight) return meridian_point(P, u, 1.0, 0.0, qu);  // (a segment has no angle)
  const double ang = u * P.sweep;
  return meridian_point(P, u, std::cos(ang), std::sin(ang), qu);
}

// Unit vectors e1, e2 normal to unit axis a: azimuths about it are measured from e1.
void axis_frame(const Vec3& a, Vec3* e1, Vec3* e2) {
  const Vec3 any = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *e1 = a.cross(any).normalized();
  *e2 = a.cross(*e1);
}
void axis_frame(const Patch& P, Vec3* e1, Vec3* e2) { axis_frame(P.a, e1, e2); }

// Patch P cut into boxes (profile fraction x azimuth) by patches_apart and
// patches_at_least: its frame, and the sizes their bounds need: |x_u| (the
// profile's length), the largest |x_th| (the largest radius) and |x_uu|.
struct BoxedPatch {
  const Patch& P;
  Vec3 e1, e2;
  double len, rmax, curv;
  explicit BoxedPatch(const Patch& p)
      : P(p),
        len(patch_profile_length(p)),
        rmax(patch_max_radius(p)),
        curv(p.straight ? 0.0 : len * len / p.rho) {
    axis_frame(P, &e1, &e2);
  }
  // The box of half-widths (du, dt) around meridian point q (derivative qu)
  // at the azimuth of cosine ct and sine st: its centre x, the radial and
  // azimuthal directions there, x's first derivatives, and the radius of a
  // ball around x holding the whole box.
  struct Box {
    Vec3 x, er, et, xu, xt;
    double prof, azi;
    // A point of the box, at meridian point q' (|q' - q| <= prof) and azimuth
    // th + d, is from x (law of cosines about the axis)
    //   |x' - x|^2 = |q' - q|^2 + 4 q'_r q_r sin^2(d / 2) <= prof^2 + rbox q_r dt^2
    // (rbox >= q'_r): a ball of that radius holds the box, not prof + azi.
    double ball;
    bool smooth;  // x(u, th) is smooth over the box (off the axis throughout)
    // A straight path of parameters across the box, x(t), has speed
    // x_u du + x_th dt (at most these half-widths), with x_u in the meridian
    // plane and x_th along the azimuth: orthogonal. Its acceleration is
    // x_uu du^2 - rho e_r dt^2 in the meridian plane plus 2 r_u du dt along
    // the azimuth (|x_uu| = len^2 / rho_P, |r_u| <= len).
    double a;     // bound on |x'|: the length of such a path
    double rest;  // half the bound on |x''|
  };
  // (Inlined into the proofs' loops: called out of line, as patch_box's third
  // call site made it, it cost 1 % of the query's instructions.)
  [[gnu::always_inline]] Box box(Vec2 q, const Vec2& qu, double ct, double st, double du, double dt) const {
    Box b;
    const bool clamped = q.x() < 0;
    q.x() = std::max(q.x(), 0.0);
    b.er = ct * e1 + st * e2;
    b.et = ct * e2 - st * e1;
    b.x = P.o + q.x() * b.er + q.y() * P.a;
    b.prof = du * len;
    // The box's points are at most q.x() + prof from the axis (and rmax).
    const double rbox = std::min(rmax, q.x() + b.prof);
    b.azi = dt * rbox;
    b.ball = std::sqrt(b.prof * b.prof + rbox * q.x() * dt * dt);
    b.smooth = !clamped && q.x() - b.prof >= 0;
    b.xu = qu.x() * b.er + qu.y() * P.a;
    b.xt = q.x() * b.et;
    b.a = std::sqrt(b.prof * b.prof + b.azi * b.azi);
    const double in_plane = curv * du * du + rbox * dt * dt, across = 2 * len * du * dt;
    b.rest = 0.5 * std::sqrt(in_plane * in_plane + across * across);
    return b;
  }
};

// The point of P at meridian point q and the azimuth of cosine c and sine s
// about P's axis frame (axis_frame) e1, e2.
Vec3 framed_point(const Patch& P, const Vec3& e1, const Vec3& e2, const Vec2& q, double c, double s) {
  return P.o + std::max(q.x(), 0.0) * (c * e1 + s * e2) + q.y() * P.a;
}

// patch_point with P's axis frame given.
Vec3 framed_point(const Patch& P, const Vec3& e1, const Vec3& e2, double u, double th) {
  return framed_point(P, e1, e2, meridian_point(P, u), std::cos(th), std::sin(th));
}

}  // namespace

Vec3 patch_point(const Patch& P, double u, double th) {
  Vec3 e1, e2;
  axis_frame(P, &e1, &e2);
  return framed_point(P, e1, e2, u, th);
}

PatchBox patch_box(const Patch& P, double um, double tm, double du, double dt) {
  const BoxedPatch bp(P);
  Vec2 qu;
  const Vec2 q = meridian_point(P, um, &qu);
  const BoxedPatch::Box b = bp.box(q, qu, std::cos(tm), std::sin(tm), du, dt);
  return {b.x, b.ball, b.a, b.rest};
}

namespace {
// The plane distance from q (in Q's half-plane, rho >= 0) to Q's arc or
// segment, and its nearest point *best: the nearer end, or the foot on the
// arc's circle (the segment's line) when it falls within the arc (segment).
// win: Q's Gauss window (unused for a segment).
double nearest_local(const Patch& Q, const GaussWindow& win, const Vec2& q, Vec2* best) {
  *best = Q.p0;
  double d = (q - Q.p0).norm();
  if (const double d1 = (q - Q.p1).norm(); d1 < d) d = d1, *best = Q.p1;
  if (Q.straight) {
    const Vec2 s = Q.p1 - Q.p0;
    const double len2 = s.squaredNorm();
    const double t = len2 > 0 ? (q - Q.p0).dot(s) / len2 : -1.0;
    if (t > 0 && t < 1) {
      const Vec2 foot = Q.p0 + t * s;
      if (const double df = (q - foot).norm(); df < d) d = df, *best = foot;
    }
  } else {
    const Vec2 v = q - Q.c;
    const double D = v.norm();
    if (D > 0 && v.dot(win.mid) >= win.cos_h * D) {
      const Vec2 foot = Q.c + Q.rho * v / D;
      if (const double df = std::abs(D - Q.rho); foot.x() >= 0 && df < d) d = df, *best = foot;
    }
  }
  return d;
}
}  // namespace

double patch_nearest(const Patch& Q, const Vec3& x, Vec3* y) {
  Vec3 er;
  const Vec2 q = patch_local(Q, x, &er);
  Vec2 best;
  const double d = nearest_local(Q, gauss_window(Q), q, &best);
  *y = patch_world(Q, best, er);
  return d;
}

namespace {
// Damped Newton descent of a function of P's parameters (u, th), u kept in
// [0, 1], from `start`, until a Newton step promises less than `resolution`
// (at most 8 steps), on finite differences: patch_deep_point's, and
// patch_pair_descent's where its closed-form derivatives fail. g(q, c, s)
// is the function at meridian point q and the azimuth of cosine c and sine s
// (in bp's frame). Where the function is not convex in the azimuth, the step
// tried first there is `flat_step` radians downhill (then halved). Returns
// the parameters reached.
template <class G>
Vec2 descend_params(const Patch& P, const BoxedPatch& bp, G&& g, const Vec2& start, double resolution,
                    double flat_step) {
  auto f = [&](double u, double th) { return g(meridian_point(P, u), std::cos(th), std::sin(th)); };
  // Steps of the finite differences, in profile fraction and radians: small
  // against a patch, large against rounding (second differences lose
  // ~1e-16 / 1e-8 of the distance's scale, far below what a start needs).
  const double hu = 1e-4, ht = 1e-4;
  // The stencil's five points from three meridian points and three
  // azimuths, those at th -+ ht by angle addition: 4 trigonometric calls an
  // iteration, not 10.
  const double c_ht = std::cos(ht), s_ht = std::sin(ht);
  // (A start that is not finite, from a point on the axis or a degenerate
  // patch, starts at the middle.)
  double u = std::isfinite(start.x()) ? std::clamp(start.x(), 0.0, 1.0) : 0.5;
  double th = std::isfinite(start.y()) ? start.y() : 0.0;
  double fu = f(u, th);
  for (int it = 0; it < 8; ++it) {
    // Central differences (one-sided at the ends of [0, 1]).
    const double u_lo = std::max(0.0, u - hu), u_hi = std::min(1.0, u + hu);
    const Vec2 m = meridian_point(P, u), m_lo = meridian_point(P, u_lo), m_hi = meridian_point(P, u_hi);
    const double c = std::cos(th), s = std::sin(th);
    const double c_lo = c * c_ht + s * s_ht, s_lo = s * c_ht - c * s_ht;  // th - ht
    const double c_hi = c * c_ht - s * s_ht, s_hi = s * c_ht + c * s_ht;  // th + ht
    const double fl = g(m_lo, c, s), fh = g(m_hi, c, s), ftl = g(m, c_lo, s_lo), fth = g(m, c_hi, s_hi);
    const double f_hh = g(m_hi, c_hi, s_hi);
    const double g_u = (fh - fl) / (u_hi - u_lo), g_t = (fth - ftl) / (2 * ht);
    const double h_tt = (fth - 2 * fu + ftl) / (ht * ht);
    double h_uu = 0.0;
    if (u_hi - u > 0 && u - u_lo > 0) h_uu = (fh - 2 * fu + fl) / (hu * hu);
    const double h_ut = (f_hh - fh - fth + fu) / ((u_hi - u) * ht);
    // Newton step on (u, th) when the Hessian is positive definite, else on th
    // alone (u then follows its gradient to the nearer end).
    double su, st;
    bool last = false;  // the Newton step's predicted decrease is below the resolution
    const double det = h_uu * h_tt - h_ut * h_ut;
    if (h_uu > 0 && det > 0) {
      su = -(h_tt * g_u - h_ut * g_t) / det;
      st = -(h_uu * g_t - h_ut * g_u) / det;
      last = -0.5 * (g_u * su + g_t * st) <= resolution;
    } else {
      st = h_tt > 0 ? -g_t / h_tt : (g_t > 0 ? -flat_step : flat_step);
      su = g_u > 0 ? -1.0 : 1.0;
    }
    st = std::clamp(st, -0.5, 0.5);
    // Damped: halve until the distance goes down.
    bool moved = false;
    for (double lam = 1.0; lam > 1e-3; lam *= 0.5) {
      const double un = std::clamp(u + lam * su, 0.0, 1.0), tn = th + lam * st;
      const double fn = f(un, tn);
      if (fn < fu) {
        moved = std::abs(un - u) > 1e-9 || std::abs(tn - th) * bp.rmax > 1e-9 * (bp.rmax + bp.len);
        u = un, th = tn, fu = fn;
        break;
      }
    }
    if (!moved || last) break;
  }
  return Vec2(u, th);
}

// P's parameters (profile fraction u, azimuth th in the frame e1, e2) of a
// world point x near it (u unclamped).
Vec2 patch_params(const Patch& P, const Vec3& e1, const Vec3& e2, const Vec3& x) {
  Vec3 er;
  const Vec2 q = patch_local(P, x, &er);
  const double th = std::atan2(er.dot(e2), er.dot(e1));
  // (A patch of no length: its middle.)
  if (P.straight) {
    const Vec2 d = P.p1 - P.p0;
    const double len2 = d.squaredNorm();
    return Vec2(len2 > 0 ? (q - P.p0).dot(d) / len2 : 0.5, th);
  }
  const Vec2 v = q - P.c;
  const double phi = std::atan2(P.d0.x() * v.y() - P.d0.y() * v.x(), P.d0.dot(v));
  return Vec2(P.sweep != 0 ? phi / P.sweep : 0.5, th);
}
}  // namespace

namespace {
// The distance from P's point at (u, th) to Q (patch_nearest's), with its
// first and second derivatives in (u, th), in closed form. In Q's meridian
// half-plane the distance is h(r, z) = |q - foot|, the foot on Q's nearest
// feature: an end point, the arc's circle or the segment's line. Its
// gradient there is the unit w from the foot to q, its Hessian k t t^T (t
// normal to w): k = 1/d at an end, s/D on the circle (D = |q - c|, s the side
// of the circle q is on), 0 on the line. About Q's axis r = |x - axis|, whose
// Hessian is e_phi e_phi^T / r, so in the world grad = w_r e_r + w_z a and
// Hess = k t t^T + (w_r / r) e_phi e_phi^T. P's point is x(u, th) = o +
// m_r(u) e_R(th) + m_z(u) a_P, with m(u) P's meridian point.
// (ca, sa): the cosine and sine of the arc's angle u * sweep (unused for a
// segment); (c, s): those of the azimuth.
PatchPairJet pair_jet(const Patch& P, const BoxedPatch& bp, const Patch& Q, const GaussWindow& win, double u,
                      double ca, double sa, double c, double s) {
  PatchPairJet j;
  Vec2 mu;
  const Vec2 m = meridian_point(P, u, ca, sa, &mu);
  const Vec2 muu = P.straight ? Vec2::Zero() : Vec2(-P.sweep * P.sweep * (m - P.c));
  const Vec3 eR = c * bp.e1 + s * bp.e2, eT = c * bp.e2 - s * bp.e1;
  const Vec3 x = P.o + std::max(m.x(), 0.0) * eR + m.y() * P.a;
  Vec3 er;
  const Vec2 q = patch_local(Q, x, &er);
  Vec2 best;
  j.f = nearest_local(Q, win, q, &best);
  const double r = q.x();
  if (!(j.f > 0) || !(r > 1e-12 * (r + std::abs(q.y()) + 1)) || m.x() < 0) return j;
  const Vec2 w = (q - best) / j.f;
  double k = 0;
  if (best == Q.p0 || best == Q.p1) {
    k = 1 / j.f;
  } else if (!Q.straight) {
    const double D = (q - Q.c).norm();
    k = (D >= Q.rho ? 1.0 : -1.0) / D;
  }
  const Vec3 grad = w.x() * er + w.y() * Q.a;
  const Vec3 t3 = -w.y() * er + w.x() * Q.a;
  const Vec3 ephi = Q.a.cross(er);
  const double beta = w.x() / r;
  const Vec3 xu = mu.x() * eR + mu.y() * P.a, xt = m.x() * eT;
  const Vec3 xuu = muu.x() * eR + muu.y() * P.a, xut = mu.x() * eT, xtt = -m.x() * eR;
  const double tu = t3.dot(xu), tt = t3.dot(xt), pu = ephi.dot(xu), pt = ephi.dot(xt);
  j.fu = grad.dot(xu);
  j.ft = grad.dot(xt);
  j.fuu = k * tu * tu + beta * pu * pu + grad.dot(xuu);
  j.fut = k * tu * tt + beta * pu * pt + grad.dot(xut);
  j.ftt = k * tt * tt + beta * pt * pt + grad.dot(xtt);
  j.smooth = true;
  return j;
}
PatchPairJet pair_jet(const Patch& P, const BoxedPatch& bp, const Patch& Q, const GaussWindow& win, double u, double th) {
  const double ang = P.straight ? 0.0 : u * P.sweep;
  return pair_jet(P, bp, Q, win, u, std::cos(ang), std::sin(ang), std::cos(th), std::sin(th));
}
}  // namespace

PatchPairJet patch_pair_jet(const Patch& P, const Patch& Q, double u, double th) {
  return pair_jet(P, BoxedPatch(P), Q, gauss_window(Q), u, th);
}

double patch_pair_descent(const Patch& P, const Patch& Q, const Vec2& start, double resolution, Vec3* x, Vec3* y,
                          bool each_alone) {
  const BoxedPatch bp(P);  // its axis frame, and the sizes for the stop test
  // patch_nearest's distance, with Q's window computed once.
  const GaussWindow win = gauss_window(Q);
  auto g = [&](const Vec2& q, double c, double s) {
    Vec2 best;
    return nearest_local(Q, win, patch_local(Q, framed_point(P, bp.e1, bp.e2, q, c, s)), &best);
  };
  // Damped Newton steps on the closed-form derivatives (pair_jet), u kept
  // in [0, 1], until a step promises less than the resolution; where the
  // distance has no derivatives (0, or a point on Q's axis) the finite
  // differences take over. (Measured on the motion probe, M instructions for
  // 600 queries at eps 1e-5 / 1e-3 / 1e-7 / tol 1e-6: finite differences
  // 140.2 / 110.2 / 280.3 / 199.9, these 134.9 / 107.3 / 270.7 / 194.4:
  // a step evaluates one jet, about 600 instructions, where the differences
  // took five points before their line search's. Up to 16
  // steps: with 8, 40 of the 1250 descents stopped short of their minimum,
  // and the query paid more for the worse pairs (137.5 at eps 1e-5); capping
  // the halvings at 1/32 cost more still, 141.7.)
  // The iterates' cosines and sines (of the arc's angle u * sweep and of
  // the azimuth) follow the steps by turn(): a jet's two libm calls were a
  // third of its cost.
  double u = std::isfinite(start.x()) ? std::clamp(start.x(), 0.0, 1.0) : 0.5;
  double th = std::isfinite(start.y()) ? start.y() : 0.0;
  const double sweep = P.straight ? 0.0 : P.sweep;
  double ca = std::cos(u * sweep), sa = std::sin(u * sweep), c = std::cos(th), s = std::sin(th);
  PatchPairJet j = pair_jet(P, bp, Q, win, u, ca, sa, c, s);
  bool rough = false;  // stopped where the derivatives do not hold
  for (int it = 0; it < 16; ++it) {
    if (!j.smooth) {
      rough = j.f > 0;
      break;
    }
    double su, st;
    bool last = false;  // the Newton step's predicted decrease is below the resolution
    const double det = j.fuu * j.ftt - j.fut * j.fut;
    const bool convex = j.fuu > 0 && det > 0;
    if (convex) {
      su = -(j.ftt * j.fu - j.fut * j.ft) / det;
      st = -(j.fuu * j.ft - j.fut * j.fu) / det;
      if ((u <= 0 && su < 0) || (u >= 1 && su > 0)) {  // against an end of [0, 1]: the azimuth alone
        su = 0;
        st = j.ftt > 0 ? -j.ft / j.ftt : 0;
      }
      last = -0.5 * (j.fu * su + j.ft * st) <= resolution;
    } else {
      // Not convex: Newton in each parameter where it is, else downhill
      // (the whole profile, or 0.05 rad), then halved.
      st = j.ftt > 0 ? -j.ft / j.ftt : (j.ft > 0 ? -0.05 : 0.05);
      su = j.fuu > 0 ? -j.fu / j.fuu : (j.fu > 0 ? -1.0 : 1.0);
    }
    st = std::clamp(st, -0.5, 0.5);
    // The step (du, dt), halved until f decreases; false when it never does.
    auto step = [&](double du, double dt) {
      for (double lam = 1.0; lam > 1e-3; lam *= 0.5) {
        const double un = std::clamp(u + lam * du, 0.0, 1.0), tn = th + lam * dt;
        double can = ca, san = sa, cn = c, sn = s;
        turn((un - u) * sweep, &can, &san);
        turn(tn - th, &cn, &sn);
        const PatchPairJet jn = pair_jet(P, bp, Q, win, un, can, san, cn, sn);
        if (jn.f < j.f) {
          const bool moved = std::abs(un - u) > 1e-9 || std::abs(tn - th) * bp.rmax > 1e-9 * (bp.rmax + bp.len);
          u = un, th = tn, j = jn;
          ca = can, sa = san, c = cn, s = sn;
          return moved;
        }
      }
      return false;
    };
    bool moved = step(su, st);
    // Not convex: the step in both parameters at once (each its own Newton
    // step or a fixed one) may find no decrease where Q's nearest point
    // changes feature; then each parameter alone.
    if (!moved && each_alone && !convex) {
      const PatchPairJet at = j;
      if (at.ftt > 0) moved = step(0.0, std::clamp(-at.ft / at.ftt, -0.5, 0.5));
      if (!moved && at.fuu > 0) moved = step(-at.fu / at.fuu, 0.0);
    }
    if (!moved || last) break;
  }
  if (rough) {
    const Vec2 p = descend_params(P, bp, g, Vec2(u, th), resolution, 0.05);
    *x = framed_point(P, bp.e1, bp.e2, p.x(), p.y());
  } else {
    *x = framed_point(P, bp.e1, bp.e2, meridian_point(P, u, ca, sa, nullptr), c, s);
  }
  return patch_nearest(Q, *x, y);
}

double patch_pair_descent(const Patch& P, const Patch& Q, const Vec3& near, double resolution, Vec3* x, Vec3* y) {
  Vec3 e1, e2;
  axis_frame(P, &e1, &e2);
  return patch_pair_descent(P, Q, patch_params(P, e1, e2, near), resolution, x, y);
}

Vec3 patch_deep_point(const Patch& P, const Patch& Q, const Vec3& near, double side, double resolution) {
  const BoxedPatch bp(P);
  auto g = [&](const Vec2& q, double c, double s) {
    return side * patch_surface_function(Q, patch_local(Q, framed_point(P, bp.e1, bp.e2, q, c, s)));
  };
  // (A signed function has no minimum near a crossing: the first steps are
  // long, 0.05 rad took 8 steps to reach a sixth of a sphere zone's depth.)
  const Vec2 p = descend_params(P, bp, g, patch_params(P, bp.e1, bp.e2, near), resolution, 0.5);
  return framed_point(P, bp.e1, bp.e2, p.x(), p.y());
}

bool patch_crossing_point(const Patch& P, const Patch& Q, const Vec3& lo, const Vec3& hi, Vec3* out) {
  Vec3 e1, e2;
  axis_frame(P, &e1, &e2);
  // (profile fraction, azimuth) of a point of P.
  auto params = [&](const Vec3& x, double* u, double* th) {
    const Vec2 p = patch_params(P, e1, e2, x);
    *u = p.x(), *th = p.y();
  };
  auto point = [&](double u, double th) { return framed_point(P, e1, e2, u, th); };
  auto g = [&](const Vec3& x) { return patch_surface_function(Q, patch_local(Q, x)); };
  double u0, t0, u1, t1;
  params(lo, &u0, &t0);
  params(hi, &u1, &t1);
  if (t1 - t0 > M_PI) t1 -= 2 * M_PI;  // the shorter way round
  if (t0 - t1 > M_PI) t1 += 2 * M_PI;
  double s0 = 0, s1 = 1;
  const double g0 = g(point(u0, t0)), g1 = g(point(u1, t1));
  if (!((g0 < 0 && g1 > 0) || (g0 > 0 && g1 < 0))) return false;
  Vec3 x = lo;
  for (int it = 0; it < 60; ++it) {
    const double sm = 0.5 * (s0 + s1);
    x = point(u0 + sm * (u1 - u0), t0 + sm * (t1 - t0));
    const double gm = g(x);
    if (gm == 0) break;
    if ((gm < 0) == (g0 < 0)) s0 = sm; else s1 = sm;
  }
  Vec3 cq;
  const double scale = std::max(patch_extent(Q, &cq), 1e-300);
  if (!patch_contains_local(Q, patch_local(Q, x), 1e-9 * scale)) return false;
  *out = x;
  return true;
}

bool patches_apart(const Patch& P, const Patch& Q, double margin, int budget) {
  // Q lies in its bounding disk in its own (rho, z) half-plane and on its
  // whole surface (g_Q = 0). Both tests are 1-Lipschitz functions of Q's
  // (rho, z) (|q - disk centre|, |q - c| - rho, n . q - off), and the map to
  // that half-plane does not increase distances, so over a box of P held by a
  // ball (x, r) each stays within r of its value at x.
  //
  // Near contact that first-order test needs boxes as small as the gap. The
  // second-order one does not: with f(u, th) = g_Q(x(u, th)) over the box
  // (half-widths du, dt), f = f(m) + grad f(m) . v + R with
  //   |R| <= (H a^2 + max |x''|) / 2,
  // a and max |x''| bounding a parameter path's speed and acceleration
  // (BoxedPatch::Box), H bounding g_Q's Hessian over the ball (g_Q is
  // a distance to Q's major circle (or centre) or to a line, minus a
  // constant, in Q's meridian half-plane: the Hessian's norm is at most 1/D in
  // that half-plane plus 1/rho about Q's axis, D the distance to the circle
  // (or centre) and rho to the axis; a line in the half-plane gives |n_r|/rho),
  // and |grad g_Q| = 1. So the box misses Q's surface when
  // |f(m)| > |f_u| du + |f_th| dt + |R|: boxes need only shrink to about
  // sqrt(gap / curvature).
  Vec2 dc;
  double dr;
  patch_disk(Q, &dc, &dr);
  const BoxedPatch bp(P);
  struct Box { double u0, u1, t0, t1; };
  Box stack[64];
  int n = 0, evals = 0;
  constexpr int kSectors = 16;
  for (int k = kSectors - 1; k >= 0; --k)
    stack[n++] = {0.0, 1.0, -M_PI + k * (2 * M_PI / kSectors), -M_PI + (k + 1) * (2 * M_PI / kSectors)};
  while (n > 0) {
    const Box b = stack[--n];
    if (++evals > budget) return false;
    const double um = 0.5 * (b.u0 + b.u1), tm = 0.5 * (b.t0 + b.t1);
    const double du = 0.5 * (b.u1 - b.u0), dt = 0.5 * (b.t1 - b.t0);
    Vec2 qu;
    const Vec2 q = meridian_point(P, um, &qu);
    const BoxedPatch::Box bx = bp.box(q, qu, std::cos(tm), std::sin(tm), du, dt);
    const double prof = bx.prof, azi = bx.azi;
    const double r = bx.ball + margin;
    Vec3 erq;
    const Vec2 qc = patch_local(Q, bx.x, &erq);
    if ((qc - dc).norm() - dr > r) continue;                      // outside Q's bounding torus
    const double g = patch_surface_function(Q, qc);
    if (std::abs(g) > r) continue;                                // off Q's surface
    // The second-order test, where the box is smooth (r >= 0 throughout) and
    // g_Q is smooth over the ball.
    const double rho_min = qc.x() - bx.ball;
    if (bx.smooth && rho_min > 0) {
      double H = Q.straight ? std::abs(Q.n.x()) / rho_min : 0.0;
      Vec2 n2 = Q.n;
      bool smooth = true;
      if (!Q.straight) {
        const Vec2 v = qc - Q.c;
        const double D = v.norm(), d_min = D - bx.ball;
        smooth = d_min > 0;
        if (smooth) {
          n2 = v / D;
          H = 1.0 / d_min + (Q.c.x() == 0 ? 0.0 : 1.0 / rho_min);
        }
      }
      if (smooth) {
        const Vec3 grad = n2.x() * erq + n2.y() * Q.a;
        const double first = std::abs(grad.dot(bx.xu)) * du + std::abs(grad.dot(bx.xt)) * dt;
        const double second = 0.5 * H * bx.a * bx.a + bx.rest;
        if (std::abs(g) > first + second + margin) continue;
      }
    }
    if (n + 2 > 64) return false;
    if (prof >= azi) {
      stack[n++] = {b.u0, um, b.t0, b.t1};
      stack[n++] = {um, b.u1, b.t0, b.t1};
    } else {
      stack[n++] = {b.u0, b.u1, b.t0, tm};
      stack[n++] = {b.u0, b.u1, tm, b.t1};
    }
  }
  return true;
}

bool patches_at_least(const Patch& P, const Patch& Q, double cut, double margin, int budget, double* lower,
                      int* evals_out, Vec2* closer, Vec2* seen) {
  // The distance from x to Q's patch is the least of up to three pieces, each
  // a smooth function of x away from Q's axis: the distances to Q's two end
  // circles (|q - p_i| in Q's half-plane) and, where x's direction from the
  // arc's centre (or its projection on the segment's line) lies in the arc
  // (segment), the distance to the arc's circle | |q - c| - rho | (the line's
  // |n . q - off|). Over a ball (x, r) the direction moves by at most
  // asin(r / |q - c|) and the projection by r, so a piece left out at the
  // centre stays out over the box when its window test fails with that slack;
  // the least of the pieces kept bounds the distance below. Each piece is
  // 1-Lipschitz (first order: f(x) - r) and, where smooth, has gradient norm 1
  // and a Hessian bounded as in patches_apart (1/D for the distance to a point
  // of Q's half-plane, plus 1/rho about Q's axis; |n_r|/rho for the line), which
  // gives the second-order bound of patches_apart.
  const BoxedPatch bp(P);
  Vec2 disk_c;
  double disk_r;
  patch_disk(Q, &disk_c, &disk_r);
  // Q's window: the arc's (its Gauss window, single here), or the segment.
  double seg_len = 0;
  Vec2 dir(1, 0);
  const GaussWindow win = gauss_window(Q);
  const Vec2& mid = win.mid;
  const double cos_h = win.cos_h, sin_h = win.sin_h;
  if (Q.straight) {
    seg_len = (Q.p1 - Q.p0).norm();
    if (seg_len > 0) dir = (Q.p1 - Q.p0) / seg_len;
  }
  // Boxes carry the cosines and sines of their middle angles (azimuth, and
  // the arc's angle at the middle profile fraction), updated by angle
  // addition with the half-widths of each level, computed once a level.
  // The azimuth's halves and the sectors' middles are the same for every call
  // (the sectors are fixed): a table built once.
  struct Box { double um, du, cu, su, tm, dt, ct, st; int lu, lt; };
  struct HalfAngle { double c, s; };
  constexpr int kSectors = 8;
  struct AzimuthHalves {
    HalfAngle h[64];
    HalfAngle mid[kSectors];  // the sectors' middles
    AzimuthHalves() {
      for (int k = 0; k < 64; ++k) {
        const double a = std::ldexp(M_PI / kSectors, -(k + 1));
        h[k] = {std::cos(a), std::sin(a)};
      }
      for (int k = 0; k < kSectors; ++k) {
        const double tm = -M_PI + (k + 0.5) * (2 * M_PI / kSectors);
        mid[k] = {std::cos(tm), std::sin(tm)};
      }
    }
  };
  static const AzimuthHalves ht;
  HalfAngle hu[64];  // level k: half of the level's half-width
  int nu = 0;
  auto half_angle = [](HalfAngle* table, int* filled, int level, double half0) {
    while (*filled <= level) {
      const double h = std::ldexp(half0, -(*filled + 1));
      table[*filled] = {std::cos(h), std::sin(h)};
      ++*filled;
    }
    return table[level];
  };
  constexpr int kOpen = 64;  // depth first: the stack holds the sectors and one path
  Box open[kOpen];
  int n = 0, evals = 0;
  const Vec2 none(kInf, 0.0);  // no point (seen, when the proof passes or meets a closer one)
  double nearest = kInf;       // the least centre distance so far (seen)
  Vec2 nearest_at = none;
  auto done = [&](bool ok) {
    if (evals_out) *evals_out = evals;
    if (seen) *seen = ok ? none : nearest_at;
    return ok;
  };
  const double sweep = P.straight ? 0.0 : P.sweep;
  const double cu0 = std::cos(0.5 * sweep), su0 = std::sin(0.5 * sweep);
  // The sectors nearest Q (their middle points to Q's disk) are searched
  // first: a proof clears every box in any order, a failure ends sooner.
  int order[kSectors];
  {
    const Vec2 q0 = meridian_point(P, 0.5, cu0, su0, nullptr);
    double key[kSectors];
    for (int k = 0; k < kSectors; ++k) {
      key[k] = (patch_local(Q, framed_point(P, bp.e1, bp.e2, q0, ht.mid[k].c, ht.mid[k].s)) - disk_c).squaredNorm();
      order[k] = k;
    }
    std::sort(order, order + kSectors, [&](int a, int b) { return key[a] > key[b]; });
  }
  for (int k : order) {
    const double tm = -M_PI + (k + 0.5) * (2 * M_PI / kSectors);
    open[n++] = {0.5, 0.5, cu0, su0, tm, M_PI / kSectors, ht.mid[k].c, ht.mid[k].s, 0, 0};
  }
  double least = std::numeric_limits<double>::infinity();
  while (n > 0) {
    const Box b = open[--n];
    if (++evals > budget) return done(false);
    const double du = b.du, dt = b.dt;
    Vec2 qu;
    const Vec2 q = meridian_point(P, b.um, b.cu, b.su, &qu);
    const BoxedPatch::Box bx = bp.box(q, qu, b.ct, b.st, du, dt);
    const double prof = bx.prof, azi = bx.azi;
    const double r = bx.ball;  // every point of the box is within r of x
    Vec3 erq;
    const Vec2 qq = patch_local(Q, bx.x, &erq);
    // Q lies in its bounding disk (in its meridian half-plane): a box whose
    // ball stays the cut away from that disk clears without Q's pieces.
    const double to_disk = (qq - disk_c).norm() - disk_r - r - margin;
    if (to_disk >= cut) {
      least = std::min(least, to_disk);
      continue;
    }
    const double rho_min = qq.x() - r;  // distance to Q's axis over the ball
    double lb = std::numeric_limits<double>::infinity();
    double truth = lb;  // the distance from x itself to Q's patch
    // A piece of value f, unit gradient grad (in Q's (rho, z)) and a lower
    // bound lam <= 0 on its Hessian's eigenvalues over the ball (NaN: not
    // smooth there). For the circle's and the line's pieces f = |s| >=
    // sign(s(x)) s, and the bound is that of the smooth sign(s(x)) s (s may
    // change sign in the box: the bound is then below 0). Only a lower bound
    // on f is wanted, so only the Hessian's negative part counts: in
    // cylindrical coordinates about Q's axis the Hessian of a function of
    // (rho, z) is its plane Hessian plus f_rho / rho about the axis, and the
    // plane Hessian of a distance to a point is positive semi-definite, of
    // |n . q - off| zero. (A signed form, with P's own curvature and the
    // gradient's movement over the ball, proves smaller gaps in fewer boxes
    // but cost more than it saved on the bench's motion: +4 % instructions.)
    // (grad_lam(&grad, &lam) supplies them, only for a piece the first-order
    // bound leaves below the cut: most pieces of most boxes clear without.)
    // The gradient of the piece with the least bound (of those that computed
    // one): a box that splits visits first the half it points away from,
    // where a closer point than the cut is likeliest.
    Vec3 down = Vec3::Zero();
    double down_bound = std::numeric_limits<double>::infinity();
    auto piece = [&](double f, auto&& grad_lam) {
      double bound = f - r;
      if (bound - margin < cut && bx.smooth) {
        Vec2 grad;
        double lam;
        grad_lam(&grad, &lam);
        if (!std::isnan(lam)) {
          const Vec3 g = grad.x() * erq + grad.y() * Q.a;
          bound = std::max(bound, f - std::abs(g.dot(bx.xu)) * du - std::abs(g.dot(bx.xt)) * dt +
                                      0.5 * lam * bx.a * bx.a - bx.rest);
          if (bound < down_bound) down_bound = bound, down = g;
        }
      }
      lb = std::min(lb, bound - margin);
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // f_rho / rho for the distance to a point at radius pr of Q's half-plane,
    // over the ball (f >= f_min, rho >= rho_min > 0): f_rho = (rho - pr) / f.
    auto azimuthal = [&](double pr, double f_min) {
      if (pr <= rho_min) return 0.0;
      return -std::min(1.0, (pr - rho_min) / f_min) / rho_min;
    };
    for (const Vec2& pe : {Q.p0, Q.p1}) {
      const Vec2 v = qq - pe;
      const double f = v.norm();
      truth = std::min(truth, f);
      // A pole (pr = 0) is a point: smooth wherever f > 0.
      piece(f, [&](Vec2* grad, double* lam) {
        const bool smooth = f - r > 0 && (pe.x() <= 0 || rho_min > 0);
        *grad = f > 0 ? Vec2(v / f) : Vec2(1, 0);
        *lam = smooth ? (pe.x() <= 0 ? 0.0 : azimuthal(pe.x(), f - r)) : nan;
      });
    }
    if (Q.straight) {
      if (seg_len > 0) {
        const double t = (qq - Q.p0).dot(dir), s = Q.n.dot(qq) - Q.off, f = std::abs(s);
        if (t >= 0 && t <= seg_len) truth = std::min(truth, f);
        if (t >= -r && t <= seg_len + r) {
          // Hessian sign(s) n_r / rho about the axis.
          piece(f, [&](Vec2* grad, double* lam) {
            const double nr = s >= 0 ? Q.n.x() : -Q.n.x();
            const bool smooth = nr >= 0 || rho_min > 0;
            *grad = s >= 0 ? Q.n : Vec2(-Q.n);
            *lam = smooth ? (nr >= 0 ? 0.0 : nr / rho_min) : nan;
          });
        }
      }
    } else {
      const Vec2 v = qq - Q.c;
      const double D = v.norm(), s = D - Q.rho, f = std::abs(s);
      const double c = D > 0 ? v.dot(mid) / D : 1.0;  // cos of the angle from the window's middle
      if (D > 0 && c >= cos_h) truth = std::min(truth, f);
      bool active = !(D > r) || cos_h <= 0 || c >= cos_h;  // (cos_lim below is at most cos_h)
      if (!active) {
        const double sd = r / D, cd = std::sqrt(std::max(0.0, 1 - sd * sd));
        const double cos_lim = cos_h * cd - sin_h * sd;  // cos(half + delta)
        active = cos_lim <= 1e-12 || c >= cos_lim - 1e-12;
      }
      if (active) {
        // Outside the tube f = D - rho: D's Hessian (a distance to a point of
        // the half-plane). Inside f = rho - D: minus it, at least -1/D in the
        // plane and -|D_rho| / rho about the axis.
        piece(f, [&](Vec2* grad, double* lam) {
          const double D_min = D - r;
          const bool smooth = D_min > 0 && (Q.c.x() == 0 || rho_min > 0);
          *lam = nan;
          if (smooth) {
            if (s > 0) *lam = Q.c.x() == 0 ? 0.0 : azimuthal(Q.c.x(), D_min);
            else *lam = -1.0 / D_min - (Q.c.x() == 0 ? 0.0 : 1.0 / rho_min);
          }
          *grad = D > 0 ? Vec2((s >= 0 ? 1.0 : -1.0) * v / D) : Vec2(1, 0);
        });
      }
    }
    if (truth < cut) {  // a point of P is closer: not provable
      if (closer) *closer = Vec2(b.um, b.tm);
      nearest_at = none;  // `closer` is the start, not `seen`
      return done(false);
    }
    if (truth < nearest) nearest = truth, nearest_at = Vec2(b.um, b.tm);
    if (lb >= cut) {
      least = std::min(least, lb);
      continue;
    }
    // A box this small that still does not clear sits at a minimum within
    // rounding of the cut: no box will clear it.
    if (r <= 1e-9 * (bp.rmax + bp.len) || truth - cut <= 1e-12 * (bp.rmax + bp.len)) return done(false);
    if (n + 2 > kOpen || b.lu >= 63 || b.lt >= 63) return done(false);
    if (prof >= azi) {
      const HalfAngle h = half_angle(hu, &nu, b.lu, 0.5 * sweep);
      const double first = down.dot(bx.xu) > 0 ? -1.0 : 1.0;  // popped first: pushed last
      for (double sgn : {-first, first}) {
        open[n++] = {b.um + sgn * 0.5 * du, 0.5 * du, b.cu * h.c - sgn * b.su * h.s, b.su * h.c + sgn * b.cu * h.s,
                     b.tm, dt, b.ct, b.st, b.lu + 1, b.lt};
      }
    } else {
      const HalfAngle h = ht.h[b.lt];
      const double first = down.dot(bx.xt) > 0 ? -1.0 : 1.0;
      for (double sgn : {-first, first}) {
        open[n++] = {b.um, du, b.cu, b.su, b.tm + sgn * 0.5 * dt, 0.5 * dt, b.ct * h.c - sgn * b.st * h.s,
                     b.st * h.c + sgn * b.ct * h.s, b.lu, b.lt + 1};
      }
    }
  }
  *lower = least;
  return done(true);
}

namespace {

// patch_spine_at_least for one spine of T: every point of T lies within
// `tube` of circle `spine` (about T's axis) at its own azimuth. (Any set
// within `tube` of the circle at its own azimuth: patch_circle_at_least.)
bool spine_at_least(const Patch& W, const GaussWindow& win, const Circle3& spine, double tube, double cut,
                    double margin, int budget, double* lower, int* evals, const Vec3* hint) {
  const double R = spine.radius;
  // A nearly straight arc's circle lies far out (R and rho_T large): the
  // rounding of its points, of their distances and of the tube's subtraction
  // is a few ulps of those lengths, not of the patches' coordinates.
  margin += 64 * std::numeric_limits<double>::epsilon() * (spine.center.cwiseAbs().maxCoeff() + R + tube);
  // dist(y, W) at a point of the spine, less the rounding of the evaluation
  // and of y (a few ulps of the coordinates: margin).
  auto dist = [&](const Vec3& y) {
    ++*evals;
    Vec2 best;
    return nearest_local(W, win, patch_local(W, y), &best) - margin;
  };
  // A point of the spine closer than this cannot be cleared.
  const double need = cut + tube + margin;
  // The first point is the spine's nearest to the hint (where a pair that
  // cannot be cleared usually shows at once), the others follow around.
  Vec3 e1, e2;
  axis_frame(spine.normal, &e1, &e2);
  if (hint) {
    Vec3 v = *hint - spine.center;
    v -= v.dot(spine.normal) * spine.normal;
    if (const double len = v.norm(); len > 0) {
      e1 = v / len;
      e2 = spine.normal.cross(e1);
    }
  }
  struct End {
    Vec3 y;
    double d;
  };
  struct Arc {
    End a, b;
  };
  constexpr int kStart = 4, kOpen = 64;
  Arc open[kOpen];
  int n = 0;
  End first{Vec3::Zero(), 0.0}, prev = first;
  for (int k = 0; k <= kStart; ++k) {
    End e = first;
    if (k < kStart) {
      static constexpr double cs[kStart][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};  // quarter turns
      e.y = spine.center + R * (cs[k][0] * e1 + cs[k][1] * e2);
      e.d = dist(e.y);
      if (e.d < need) return false;
      if (R == 0) {  // a sphere's spine is a point
        *lower = e.d - tube;
        return true;
      }
    }
    if (k == 0) first = e;
    else open[n++] = {prev, e};
    prev = e;
  }
  double least = std::numeric_limits<double>::infinity();
  while (n > 0) {
    const Arc arc = open[--n];
    const double L2 = (arc.b.y - arc.a.y).squaredNorm();
    const double sag = R - std::sqrt(std::max(0.0, R * R - 0.25 * L2));
    const double bound = chord_bound(arc.a.d, arc.b.d, L2) - sag - margin;
    if (bound >= need) {
      least = std::min(least, bound - tube);
      continue;
    }
    if (*evals >= budget || n + 2 > kOpen) return false;
    Vec3 mid = 0.5 * (arc.a.y + arc.b.y) - spine.center;
    mid -= mid.dot(spine.normal) * spine.normal;
    const double len = mid.norm();
    if (!(len > 0)) return false;
    End m{spine.center + (R / len) * mid, 0.0};
    m.d = dist(m.y);
    if (m.d < need) return false;
    // The half with the nearer end first: a closer point is found sooner.
    if (arc.a.d < arc.b.d) {
      open[n++] = {m, arc.b};
      open[n++] = {arc.a, m};
    } else {
      open[n++] = {arc.a, m};
      open[n++] = {m, arc.b};
    }
  }
  *lower = least;
  return true;
}

}  // namespace

bool patch_spine_at_least(const Patch& W, const Patch& T, double cut, double margin, int budget, double* lower,
                          int* evals_out, const Vec3* hint) {
  int evals = 0;
  const GaussWindow win = gauss_window(W);
  // T's major circle (tube T.rho) first: exact along T's normals. Then, where
  // thinner (a short or flat arc, a segment), the circle its bounding disk's
  // centre sweeps, of that disk's radius (patch_disk): a point of T is within
  // it of the disk's centre at its own azimuth.
  bool ok = !T.straight && spine_at_least(W, win, patch_major_circle(T), T.rho, cut, margin, budget, lower, &evals, hint);
  if (!ok) {
    Vec2 dc;
    double dr;
    patch_disk(T, &dc, &dr);
    if (T.straight || dr < T.rho)
      ok = spine_at_least(W, win, patch_disk_circle(T, dc), dr, cut, margin, evals + budget, lower, &evals, hint);
  }
  if (evals_out) *evals_out = evals;
  return ok;
}

bool patch_circle_at_least(const Patch& W, const Circle3& spine, double tube, double cut, double margin, int budget,
                           double* lower, int* evals_out, const Vec3* hint) {
  int evals = 0;
  const bool ok = spine_at_least(W, gauss_window(W), spine, tube, cut, margin, budget, lower, &evals, hint);
  if (evals_out) *evals_out = evals;
  return ok;
}

PatchPairResult patch_pair_distance(const Patch& A, const Patch& B, double cutoff, double known_lower, unsigned outer) {
  Vec3 ca, cb;
  const double ea = patch_extent(A, &ca), eb = patch_extent(B, &cb);
  const double scale = std::max({ea, eb, (ca - cb).norm(), 1e-300});
  // Points built on the patches are on them to a few ulps of the coordinates.
  const double coord = std::max({ca.cwiseAbs().maxCoeff(), cb.cwiseAbs().maxCoeff(), scale});
  // Rounding of the surface functions: a few ulps of the coordinates.
  const double gtol = 1024 * std::numeric_limits<double>::epsilon() * coord;
  // Disjoint bounding tori (or any positive lower bound the caller knows, such
  // as disjoint torus tubes) separate the patches: no sign tests, and
  // sub-problems that cannot beat the cutoff are skipped.
  // The caller's bound (patch_pair_quick's) already includes the bounding tori.
  const double disk_lb = std::isfinite(known_lower) ? known_lower : patch_disk_bound(A, B);
  bool need_g = !(disk_lb > gtol);
  // Two conical patches: their hulls' distance (fast/cone_hull.h) proves them
  // apart and bounds them without normal lines, which nearly parallel axes
  // make ill-conditioned; when the hulls' closest points lie on both lateral
  // surfaces it is the distance, and the enumeration is not needed.
  double hull_lb = -kInf;
  if (A.straight && B.straight) {
    const ConeHullResult h = cone_hull_distance(A, B);
    if (h.lower > gtol) {
      hull_lb = h.lower;
      need_g = false;
      if (h.upper - h.lower <= gtol) {
        PatchPairResult r;
        r.found = r.separated = true;
        r.upper = h.upper;
        r.x = h.x;
        r.y = h.y;
        r.lower_skipped = h.lower;
        return r;
      }
    }
  }
  if (need_g) {
    // The bounding tori meet: try the cheap proof that the patches are apart
    // (boxes of the smaller patch against the other's surface), else the sign
    // tests over every candidate below.
    const bool a_small = ea <= eb;
    if (a_small ? patches_apart(A, B, gtol, 256) : patches_apart(B, A, gtol, 256)) need_g = false;
  }
  Collector c{A, B, 1e-9 * scale + 64 * std::numeric_limits<double>::epsilon() * coord, cutoff, need_g, {}};

  const Circle3 ea_c[2] = {patch_end_circle(A, 0), patch_end_circle(A, 1)};
  const Circle3 eb_c[2] = {patch_end_circle(B, 0), patch_end_circle(B, 1)};
  // Junction circles matter only to the sign tests (which need every candidate).
  if (need_g) outer = kOuterAll;
  const bool a_out[2] = {(outer & kOuterA0) != 0, (outer & kOuterA1) != 0};
  const bool b_out[2] = {(outer & kOuterB0) != 0, (outer & kOuterB1) != 0};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      if (!a_out[i] || !b_out[j]) continue;
      const Circle3& e = ea_c[i];
      const Circle3& f = eb_c[j];
      if (c.skip(circle3_circle3_lower_bound(e, f))) continue;  // closed form first
      const auto r = circle3_circle3_distance(e, f);
      c.pair(r.point_a, r.point_b);
      c.point_a(r.point_a);
      c.point_b(r.point_b);
    }
  for (int i = 0; i < 2; ++i)
    if (a_out[i]) boundary_vs_interior(c, ea_c[i], true);
  for (int j = 0; j < 2; ++j)
    if (b_out[j]) boundary_vs_interior(c, eb_c[j], false);
  interior_vs_interior(c, disk_lb);
  if (need_g) {
    nonsmooth_points(c, true);
    nonsmooth_points(c, false);
  }
  if (hull_lb > gtol) {
    // Apart whatever the enumeration found. A complete enumeration is the
    // distance; a degenerate one may have missed the minimum, so the hull
    // bound stands beside it.
    c.res.separated = true;
    if (c.res.degenerate) c.res.lower_skipped = std::min(c.res.lower_skipped, hull_lb);
    return c.res;
  }
  c.res.separated = !c.res.degenerate && (!need_g || c.gb_min > gtol || c.gb_max < -gtol ||
                                          c.ga_min > gtol || c.ga_max < -gtol);
  return c.res;
}

}  // namespace revdist
