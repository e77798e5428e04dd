// Circle-circle minimum distance in double (paper section 3.2; Vranek 2002 for
// the global-minimum certificate). The leaf kernel of the distance query.
//
// Method. One circle p is parameterised by θ and f(θ) = Z^2 + (ρ - R)^2 is the
// squared distance from P(θ) to the other circle q (Z: height over q's plane,
// ρ: distance to q's axis). Samples and a safeguarded Newton descent give a local
// minimum m = f(θ*). The points where f = m lie on the torus of minor radius √m
// around q, whose equation (|Δ|^2 + R^2 - m)^2 - 4R^2ρ^2 = 0 is a trig polynomial
// of degree 2 along p, a quartic g(t) in t = tan((θ - θ*)/2). It has a double
// root at t = 0; dividing it out leaves a quadratic whose roots bound the only
// arc where f < m can happen (f - m changes sign only at roots of g). So: if the
// quadratic has no real roots, or f at the arc's midpoint is not below m, m is
// the global minimum; otherwise descend again from that midpoint. Each round
// strictly lowers m and f has at most 4 local minima.
// Why not the degree-8 binormal polynomial: it needs a robust root finder (double
// roots on mirror-symmetric inputs, multiplicity 4 at tangency, ≡ 0 on Villarceau
// and meridian pairs) and costs several times more; the quartic test is cheap, and
// its failure mode (coefficients lost to rounding when f is nearly flat) only
// affects pairs whose minima differ by a rounding-level amount.
//
// Named degenerate configurations are decided first and answered in closed form:
// points (radius 0), a point on the other circle's axis, coaxial (incl.
// concentric coplanar), parallel planes, concentric tilted. The others run the
// general method with a guard each: circle through the other's axis (the cusp of
// f is a local max; the descent steps past it), Villarceau and meridian pairs
// (g ≡ 0: fall back to the extrema of ρ^2), a circle tangent to the other's axis
// at its minimum (all of q equidistant: infinitely many), f constant
// (infinitely many).
//
// Scale: every length is multiplied by a power of two bringing the largest of
// (radii, centre offset) near 1, so the kernel is bit-for-bit scale invariant by
// powers of two and its tolerances are plain multiples of ε.
#include "fast/circle_distance.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "fast/circle_internal.h"
#include "fast/turn.h"

namespace revdist {

namespace {

using namespace circle_detail;

struct Min {
  double th = 0, c = 1, s = 0, f = 0;
};

// Local minimum of f from th: Newton where f'' > 0, a guarded descent step
// elsewhere (near q's axis f has a cusp with f'' -> -inf), each non-Newton step
// checked to decrease f.
// (c, s): th's cosine and sine.
Min descend(const PairCoeffs& k, double th, double c, double s) {
  double trust = 0.5;  // radians; bounds every step so a step cannot jump a whole basin
  for (int it = 0; it < 60; ++it) {
    const Deriv d = sq_dist_derivs(k, c, s);
    const bool newton = d.f2 > 0;
    double step = newton ? -d.f1 / d.f2 : (d.f1 > 0 ? -trust : trust);
    if (!(std::abs(step) <= trust)) step = step < 0 ? -trust : trust;
    if (newton && std::abs(step) < 1e-4) {
      // Inside the convex basin Newton converges quadratically: take the step unchecked
      // (a check would stall on rounding noise in f once |step| ~ sqrt(ε)).
      th += step;
      turn(step, &c, &s);
      // The next error is ~step^2. Stop when that is below ε, or (away from
      // contact, f > 1e-10) when f's error f''·step^4 is far below ε·f.
      if (std::abs(step) < 1e-11 || (std::abs(step) < 1e-7 && d.f > 1e-10)) break;
      continue;
    }
    double cn = c, sn = s, fn = d.f;
    bool ok = false;
    for (int tries = 0; tries < 40; ++tries, step *= 0.5) {
      cn = c;
      sn = s;
      turn(step, &cn, &sn);
      fn = sq_dist(k, cn, sn);
      if (fn < d.f || (newton && fn == d.f)) {
        ok = true;
        break;
      }
    }
    if (!ok) break;  // no descent direction left: a local minimum within rounding
    th += step;
    c = cn;
    s = sn;
  }
  Min m;
  m.th = th;
  m.c = c;
  m.s = s;
  m.f = sq_dist(k, c, s);
  return m;
}

Min descend(const PairCoeffs& k, double th) { return descend(k, th, std::cos(th), std::sin(th)); }

// Evenly spaced samples of θ: the start of the descent (any local minimum is a
// valid start; a good one saves a round).
constexpr int kSamples = 8;
const std::array<double, 2 * kSamples>& sample_table() {
  static const std::array<double, 2 * kSamples> t = [] {
    std::array<double, 2 * kSamples> v{};
    for (int i = 0; i < kSamples; ++i) {
      v[2 * i] = std::cos(2 * kPi * i / kSamples);
      v[2 * i + 1] = std::sin(2 * kPi * i / kSamples);
    }
    return v;
  }();
  return t;
}

// The torus quartic g of the file comment, in the frame rotated to the current
// minimum, without its double root at t = 0: c4 t^2 + c3 t + c2. Returns false when
// g's largest coefficient relative to the size of its terms: 0 (within rounding)
// when g vanishes identically (Villarceau and meridian pairs: every point of p is
// at distance √m from q on the near or the far branch), small near those.
double torus_quadratic(const PairCoeffs& r, double m, double* c2, double* c3, double* c4) {
  const double R2x4 = 4 * r.R * r.R;
  double p[3], X[3], Y[3];
  trig1_to_t(r.a0 + r.R * r.R - m, r.a1, r.b1, p);
  trig1_to_t(r.x0, r.x1, r.x2, X);
  trig1_to_t(r.y0, r.y1, r.y2, Y);
  *c2 = p[1] * p[1] + 2 * p[0] * p[2] - R2x4 * (X[1] * X[1] + 2 * X[0] * X[2] + Y[1] * Y[1] + 2 * Y[0] * Y[2]);
  *c3 = 2 * p[1] * p[2] - 2 * R2x4 * (X[1] * X[2] + Y[1] * Y[2]);
  *c4 = p[2] * p[2] - R2x4 * (X[2] * X[2] + Y[2] * Y[2]);
  const double sp = std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]);
  const double sx = std::abs(X[0]) + std::abs(X[1]) + std::abs(X[2]);
  const double sy = std::abs(Y[0]) + std::abs(Y[1]) + std::abs(Y[2]);
  const double mag = sp * sp + R2x4 * (sx * sx + sy * sy);
  return std::max({std::abs(*c2), std::abs(*c3), std::abs(*c4)}) / mag;
}

// Meridian/Villarceau fallback (g ≡ 0): on every arc between axis crossings
// either f ≡ m or the far distance ≡ m, and there f = m - 4Rρ is least where ρ^2
// is greatest. The candidates are the critical points of ρ^2 = X^2 + Y^2.
bool fallback_rho_extrema(const PairCoeffs& k, Min* cur) {
  double th[16];
  const int n = rho2_critical_angles(k, th);
  bool improved = false;
  for (int i = 0; i < n; ++i) {
    if (sq_dist(k, std::cos(th[i]), std::sin(th[i])) >= cur->f) continue;
    const Min m = descend(k, th[i]);
    if (m.f < cur->f) {
      *cur = m;
      improved = true;
    }
  }
  return improved;
}

// Near-contact starts. When m is tiny the torus quartic cannot tell minima
// apart (its coefficients carry ε·scale^4 of rounding, its signal is ~m·scale^2).
// A point with f < m has |Z| < √m and |ρ^2 - R^2| < √m(2R + √m), so it lies
// next to a zero or an extremum of Z (p crossing or touching q's plane) or of
// u = ρ^2 - R^2 (p's shadow crossing or touching q): descend from each of those.
bool near_contact_starts(const PairCoeffs& k, Min* cur) {
  double th[24];
  int n = 0;
  const double A = std::hypot(k.z1, k.z2), phi = std::atan2(k.z2, k.z1);
  th[n++] = phi;
  th[n++] = phi + kPi;
  if (A > 0 && std::abs(k.z0) <= A) {
    const double w = std::acos(-k.z0 / A);
    th[n++] = phi + w;
    th[n++] = phi - w;
  }
  double X[3], Y[3], u[5], t1[5];
  trig1_to_t(k.x0, k.x1, k.x2, X);
  trig1_to_t(k.y0, k.y1, k.y2, Y);
  poly_mul(X, 2, X, 2, u);
  poly_mul(Y, 2, Y, 2, t1);
  const double R2 = k.R * k.R;
  for (int i = 0; i <= 4; ++i) u[i] += t1[i];
  u[0] -= R2;
  u[2] -= 2 * R2;
  u[4] -= R2;
  n += trig_poly_roots(u, 4, th + n);
  n += rho2_critical_angles(k, th + n);
  bool improved = false;
  for (int i = 0; i < n; ++i) {
    const Min m = descend(k, th[i]);
    if (m.f < cur->f) {
      *cur = m;
      improved = true;
    }
  }
  return improved;
}

// The rounds of the file comment from the local minimum cur. Returns whether cur improved.
bool vranek_rounds(const PairCoeffs& k, Min* cur_io) {
  Min& cur = *cur_io;
  const double f0 = cur.f;
  bool tried_fallback = false;
  // At most 4 local minima exist, so at most 4 rounds improve; 8 bounds the noise-driven ones.
  for (int round = 0; round < 8; ++round) {
    const PairCoeffs r = rotate_coeffs(k, cur.c, cur.s);
    double c2, c3, c4;
    const double flat = torus_quadratic(r, cur.f, &c2, &c3, &c4);
    // Each coefficient is a sum of products of g's terms: rounding below ~8ε·mag;
    // 64ε calls "identically zero" only what rounding can explain. Up to 1e-6 the
    // pair is so near a g ≡ 0 one that the quadratic's verdict is not trusted alone.
    if (flat <= 64 * kEps) {
      if (fallback_rho_extrema(k, &cur)) continue;
      break;
    }
    if (flat <= 1e-6 && !tried_fallback) {
      tried_fallback = true;
      if (fallback_rho_extrema(k, &cur)) continue;
    }
    const double disc = c3 * c3 - 4 * c4 * c2;
    if (disc < 0) break;  // g > 0 away from t = 0: no point of p is nearer than √m
    // Roots t = q/c4 and c2/q; as angles 2·atan2 so a root at infinity (c4 = 0) is θ = π.
    const double qq = -0.5 * (c3 + std::copysign(std::sqrt(disc), c3));
    double t1, t2;
    if (qq == 0) {
      t1 = t2 = c4 == 0 ? kPi : 0.0;
    } else {
      t1 = wrap_pi(2 * std::atan2(qq, c4));
      t2 = wrap_pi(2 * std::atan2(c2, qq));
    }
    // The arc between the roots that avoids 0; both arcs' midpoints are tried
    // since a rounding-level root near 0 makes "which arc" ambiguous.
    const double mid = 0.5 * (t1 + t2);
    const double cand[2] = {mid, mid + kPi};
    double bf = cur.f, bt = 0;
    for (double t : cand) {
      const double th = cur.th + t;
      const double f = sq_dist(k, std::cos(th), std::sin(th));
      if (f < bf) {
        bf = f;
        bt = th;
      }
    }
    if (!(bf < cur.f)) break;
    const Min next = descend(k, bt);
    if (!(next.f < cur.f)) break;
    cur = next;
  }
  return cur.f < f0;
}

struct Generic {
  Min min;
  bool infinite = false;
};

// The samples' spacing cut in kSub, with the cosines and sines of those
// angles: the descent's start is taken on it, so that a solve needs no sine
// and cosine to start (one in eight of the motion probe's was a start).
constexpr int kSub = 16;
const std::array<double, 2 * kSamples * kSub>& start_table() {
  static const std::array<double, 2 * kSamples * kSub> t = [] {
    std::array<double, 2 * kSamples * kSub> v{};
    for (int i = 0; i < kSamples * kSub; ++i) {
      v[2 * i] = std::cos(2 * kPi * i / (kSamples * kSub));
      v[2 * i + 1] = std::sin(2 * kPi * i / (kSamples * kSub));
    }
    return v;
  }();
  return t;
}

struct Start {
  double th, c, s;
};

// The best sample and the vertex of the parabola through it and its
// neighbours (clamped to their span), rounded to the start table: the
// descent's start (a start there saves Newton steps). fs: the samples.
Start sampled_start(const PairCoeffs& k, double* fs) {
  const auto& tab = sample_table();
  int best = 0;
  for (int i = 0; i < kSamples; ++i) {
    fs[i] = sq_dist(k, tab[2 * i], tab[2 * i + 1]);
    if (fs[i] < fs[best]) best = i;
  }
  const double fl = fs[(best + kSamples - 1) % kSamples], fr = fs[(best + 1) % kSamples];
  const double curv = fl - 2 * fs[best] + fr;
  double off = curv > 0 ? 0.5 * (fl - fr) / curv : 0.0;
  off = std::clamp(off, -1.0, 1.0);
  const int at = best * kSub + static_cast<int>(std::lround(off * kSub));  // in [-kSub, (kSamples + 1) kSub]
  const int n = kSamples * kSub, i = (at % n + n) % n;
  return {2 * kPi * at / n, start_table()[2 * i], start_table()[2 * i + 1]};
}

// The global minimum of f by the method of the file comment (fs: the samples).
Min least(const PairCoeffs& k, double* fs) {
  const Start st = sampled_start(k, fs);
  Min cur = descend(k, st.th, st.c, st.s);
  vranek_rounds(k, &cur);
  // Below a distance of 1e-3 (scaled) the quartic resolves f only to ~1e-13,
  // which could cost more than 1e-10 in distance: near-contact starts as well.
  if (cur.f < 1e-6 && near_contact_starts(k, &cur)) vranek_rounds(k, &cur);
  return cur;
}

// The general method of the file comment for p (parameterised) against q, in
// scaled coefficients k (lengths ~1): the minimum, and whether infinitely many
// pairs attain it.
Generic solve_generic(const PairCoeffs& k) {
  double fs[kSamples];
  Generic g;
  g.min = least(k, fs);
  const Min& cur = g.min;
  // Infinitely many closest pairs. (1) P(θ*) on q's axis: every point of q is
  // equidistant (p tangent to q's axis there; a crossing would be a cusp maximum).
  // (2) f constant along p (coaxial within rounding, Villarceau, a meridian
  // circle inside the torus), judged on the samples and then on a finer ring.
  const double noise = 64 * kEps;  // f's rounding error at scale ~1: a few ε per term
  if (std::sqrt(std::max(0.0, cur.f)) + 1 > 0 &&
      sq_dist_derivs(k, cur.c, cur.s).rho <= 16 * kEps * (1 + std::abs(k.R)) && k.R > 0) {
    g.infinite = true;
    return g;
  }
  double fmax = 0;
  for (int i = 0; i < kSamples; ++i) fmax = std::max(fmax, fs[i]);
  // f's variation is at most 2 pi * max|f'| <= 4 pi sqrt(fmax) Rp (the
  // distance to q is 1-Lipschitz, p's point moves at speed Rp). Where that is
  // within the noise (a circle tiny against its distance: unit circles 1e20
  // apart) every pair looks flat, and flatness proves nothing. No family can
  // hide there: sigma scales the largest of the radii and the centre offset
  // to about 1 and p has the larger radius, so a tiny Rp leaves the centres
  // about 1 apart, where a torus around q carries no circle of p's size but
  // its parallels (coaxial: named before the generic solve).
  const double Rp = std::sqrt(k.x1 * k.x1 + k.y1 * k.y1 + k.z1 * k.z1);
  const bool resolvable = 4 * kPi * std::sqrt(fmax) * Rp > 1e6 * noise;
  if (resolvable && fmax - cur.f <= noise) {
    bool flat = true;
    for (int i = 0; i < 4 * kSamples && flat; ++i) {
      const double th = 2 * kPi * (i + 0.5) / (4 * kSamples);
      flat = sq_dist(k, std::cos(th), std::sin(th)) - cur.f <= noise;
    }
    g.infinite = flat;
  }
  return g;
}

// Canonical argument order, so that swapping a and b gives bit-identical answers:
// the larger circle is parameterised (ties broken by the raw numbers).
bool param_is_a(const Circle3& a, const Circle3& b) {
  if (a.radius != b.radius) return a.radius > b.radius;
  for (int i = 0; i < 3; ++i)
    if (a.center[i] != b.center[i]) return a.center[i] > b.center[i];
  for (int i = 0; i < 3; ++i)
    if (a.normal[i] != b.normal[i]) return a.normal[i] > b.normal[i];
  return false;
}

struct PairAnswer {
  double dist = 0;
  Vec3 on_p, on_q;
  bool infinite = false;
};

// Point x against circle c (radius may be 0), in scaled units relative to c.
// Named case: x on c's axis, every point of c equidistant.
PairAnswer point_circle(const Vec3& x, const CircleFrame& c, double sigma) {
  PairAnswer ans;
  const Vec3 d = (x - c.center) * sigma;
  const double R = c.radius * sigma;
  const double h = d.dot(c.n), px = d.dot(c.u), py = d.dot(c.v);
  const double rho = std::sqrt(px * px + py * py);
  const double e = rho - R;
  ans.dist = std::sqrt(h * h + e * e) / sigma;
  // Frame rounding leaves an on-axis point a few ε·|d| off the axis.
  const bool on_axis = rho <= 8 * kEps * d.cwiseAbs().maxCoeff();
  ans.infinite = on_axis && R > 0;
  const Vec3 dir = on_axis ? c.u : Vec3((px * c.u + py * c.v) / rho);
  ans.on_p = c.center + c.radius * dir;
  ans.on_q = x;
  return ans;
}

// The tests of two named configurations of solve (scaled coefficients,
// lengths ~1): parallel planes (the unit normals agree to rounding), and
// concentric circles (|C_p - C_q| within the rounding of frames and offsets).
bool parallel_planes(const CircleFrame& p, const CircleFrame& q) { return p.n.cross(q.n).norm() <= 8 * kEps; }
bool concentric(const PairCoeffs& k) { return std::sqrt(k.x0 * k.x0 + k.y0 * k.y0 + k.z0 * k.z0) <= 16 * kEps; }

PairAnswer solve(const CircleFrame& p, const CircleFrame& q, double sigma) {
  // Named: points (radius 0). The larger radius is p's, so q is the point.
  if (q.radius == 0) return point_circle(q.center, p, sigma);

  PairAnswer ans;
  const PairCoeffs k = make_coeffs(p, q, sigma);
  const double Rp = p.radius * sigma, Rq = k.R;
  const double tol = 16 * kEps;                      // rounding of frames and offsets at scale ~1
  const double offset = std::sqrt(k.x0 * k.x0 + k.y0 * k.y0);  // C_p off q's axis

  if (parallel_planes(p, q)) {
    if (offset <= tol) {
      // Named: coaxial, incl. concentric coplanar. Distance constant along the circles.
      const double e = Rp - Rq;
      ans.dist = std::sqrt(k.z0 * k.z0 + e * e) / sigma;
      ans.on_q = q.center + q.radius * q.u;
      ans.on_p = p.center + p.radius * q.u;
      ans.infinite = true;
      return ans;
    }
    // Named: parallel planes. The 2D circle-circle distance plus the height.
    const Vec3 ex = (k.x0 * q.u + k.y0 * q.v) / offset;  // from C_q towards C_p, in q's plane
    double d2;
    if (offset >= Rp + Rq) {  // apart
      d2 = offset - Rp - Rq;
      ans.on_q = q.center + q.radius * ex;
      ans.on_p = p.center - p.radius * ex;
    } else if (offset <= std::abs(Rp - Rq)) {  // nested
      d2 = std::abs(Rp - Rq) - offset;
      const double sgn = Rq >= Rp ? 1 : -1;
      ans.on_q = q.center + sgn * q.radius * ex;
      ans.on_p = p.center + sgn * p.radius * ex;
    } else {  // the projections cross
      d2 = 0;
      const double x = (offset * offset + Rq * Rq - Rp * Rp) / (2 * offset);
      const double y = std::sqrt(std::max(0.0, Rq * Rq - x * x));
      const Vec3 dir = (x * ex + y * q.n.cross(ex)).normalized();
      ans.on_q = q.center + q.radius * dir;
      ans.on_p = point_circle(ans.on_q, p, sigma).on_p;
    }
    ans.dist = std::sqrt(k.z0 * k.z0 + d2 * d2) / sigma;
    return ans;
  }
  if (concentric(k)) {
    // Named: concentric, tilted planes. Both circles are great circles of
    // concentric spheres; they meet the line of the planes' intersection.
    const Vec3 L = q.n.cross(p.n).normalized();
    ans.dist = std::abs(Rp - Rq) / sigma;
    ans.on_q = q.center + q.radius * L;
    ans.on_p = p.center + p.radius * L;
    return ans;
  }
  const Generic g = solve_generic(k);
  const double X = k.x0 + k.x1 * g.min.c + k.x2 * g.min.s;
  const double Y = k.y0 + k.y1 * g.min.c + k.y2 * g.min.s;
  const double rho = std::sqrt(X * X + Y * Y);
  ans.dist = std::sqrt(std::max(0.0, g.min.f)) / sigma;
  ans.on_p = p.center + p.radius * (g.min.c * p.u + g.min.s * p.v);
  ans.on_q = q.center + q.radius * (rho > 0 ? Vec3((X * q.u + Y * q.v) / rho) : q.u);
  ans.infinite = g.infinite;
  return ans;
}

}  // namespace

namespace {
// circle3_circle3_distance_value with the two circles' frames made.
double distance_value(const Circle3& a, const CircleFrame& fa, const Circle3& b, const CircleFrame& fb) {
  const bool swap = param_is_a(a, b);  // p, parameterised, is the larger
  const CircleFrame& fp = swap ? fa : fb;
  const CircleFrame& fq = swap ? fb : fa;
  const double sigma = circle_pair_sigma(a, b);
  const PairCoeffs k = make_coeffs(fp, fq, sigma);
  // The named configurations keep their closed forms: points (q's radius is
  // the smaller), parallel planes, concentric.
  if (fq.radius == 0 || parallel_planes(fp, fq) || concentric(k)) return circle3_circle3_distance(a, b).distance;
  double fs[kSamples];
  return std::sqrt(std::max(0.0, least(k, fs).f)) / sigma;
}

CircleFrame frame_of(const Circle3& c, const CircleNormalFrame& f) {
  CircleFrame r;
  r.center = c.center;
  r.n = f.n;
  r.u = f.u;
  r.v = f.v;
  r.radius = c.radius;
  return r;
}
}  // namespace

double circle3_circle3_distance_value(const Circle3& a, const Circle3& b) {
  return distance_value(a, make_frame(a), b, make_frame(b));
}

CircleNormalFrame circle_normal_frame(const Vec3& normal) {
  CircleNormalFrame f;
  f.n = unit_normal(normal);
  plane_basis(f.n, &f.u, &f.v);
  return f;
}

double circle3_circle3_distance_value(const Circle3& a, const CircleNormalFrame& fa, const Circle3& b,
                                      const CircleNormalFrame& fb) {
  return distance_value(a, frame_of(a, fa), b, frame_of(b, fb));
}

Circle3Circle3Result circle3_circle3_distance(const Circle3& a, const Circle3& b) {
  const bool swap = param_is_a(a, b);
  const Circle3& p = swap ? a : b;
  const Circle3& q = swap ? b : a;
  const double sigma = circle_pair_sigma(a, b);
  Circle3Circle3Result r;
  if (p.radius == 0) {  // named: both radii 0, two points
    r.distance = ((p.center - q.center) * sigma).norm() / sigma;
    r.point_a = a.center;
    r.point_b = b.center;
    return r;
  }
  const PairAnswer ans = solve(make_frame(p), make_frame(q), sigma);
  r.distance = ans.dist;
  r.point_a = swap ? ans.on_p : ans.on_q;
  r.point_b = swap ? ans.on_q : ans.on_p;
  r.status = ans.infinite ? CircleCircleStatus::infinitely_many : CircleCircleStatus::ok;
  r.binormals = ans.infinite ? -1 : 0;
  return r;
}

}  // namespace revdist
