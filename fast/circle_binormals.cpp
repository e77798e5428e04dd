// Binormal lines of two circles in double (paper section 3.2, Appendix A).
//
// Circle b is parameterised by θ; with Δ = P(θ) - C_a in a's frame (X, Y, Z),
// T = P'(θ), L = Δ·T, Qp = (X, Y)·(X', Y') and ρ = |(X, Y)|, the squared distance
// to a's near (σ = +1) or far (σ = -1) point has derivative 2(L - σR·Qp/ρ). Both
// branches at once: Φ = ρ^2 L^2 - R^2 Qp^2 = 0, a trig polynomial of degree 4,
// degree 8 in t = tan(θ/2) (the paper's polynomial). Its real roots are isolated
// on two charts (so none is lost at θ = π), kept when they touch zero (double
// roots of mirror-symmetric pairs, multiplicity 4 at tangency), then polished by
// Newton on the smooth branch function L - σR·Qp/ρ and accepted only where it
// vanishes to rounding. Φ also vanishes doubly where b crosses a's axis (ρ = 0);
// those points are found as minima of ρ^2 and answered by construction: the
// lines from such a point Q to the points of a in the plane through Q normal to b.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fast/circle_distance.h"
#include "fast/circle_internal.h"

namespace revdist {

namespace {

using namespace circle_detail;

struct Line {
  double th;  // on b
  Vec3 on_a;  // world
  double dist;
};

struct Pt {
  double X, Y, Z, X1, Y1, Z1, X2, Y2, Z2;
};

Pt at(const PairCoeffs& k, double th) {
  const double c = std::cos(th), s = std::sin(th);
  Pt p;
  p.X = k.x0 + k.x1 * c + k.x2 * s;
  p.Y = k.y0 + k.y1 * c + k.y2 * s;
  p.Z = k.z0 + k.z1 * c + k.z2 * s;
  p.X1 = k.x2 * c - k.x1 * s;
  p.Y1 = k.y2 * c - k.y1 * s;
  p.Z1 = k.z2 * c - k.z1 * s;
  p.X2 = -(k.x1 * c + k.x2 * s);
  p.Y2 = -(k.y1 * c + k.y2 * s);
  p.Z2 = -(k.z1 * c + k.z2 * s);
  return p;
}

// Newton on the branch derivative ψ = L - σR·Qp/ρ from th. Returns false when it
// does not converge to a zero of ψ near th or runs into a's axis.
bool polish_branch(const PairCoeffs& k, double sigma, double* th) {
  const double th0 = *th;
  double t = th0;
  for (int it = 0; it < 60; ++it) {
    const Pt p = at(k, t);
    const double rho = std::sqrt(p.X * p.X + p.Y * p.Y);
    if (rho <= 1e-9) return false;  // the axis is answered by construction
    const double L = p.X * p.X1 + p.Y * p.Y1 + p.Z * p.Z1;
    const double Qp = p.X * p.X1 + p.Y * p.Y1;
    const double L1 = p.X1 * p.X1 + p.Y1 * p.Y1 + p.Z1 * p.Z1 + p.X * p.X2 + p.Y * p.Y2 + p.Z * p.Z2;
    const double Qp1 = p.X1 * p.X1 + p.Y1 * p.Y1 + p.X * p.X2 + p.Y * p.Y2;
    const double psi = L - sigma * k.R * Qp / rho;
    const double dpsi = L1 - sigma * k.R * (Qp1 / rho - Qp * Qp / (rho * rho * rho));
    // Size of the terms of ψ: its rounding error is a few ε times this.
    const double mag = (std::abs(p.X) + std::abs(p.Y) + std::abs(p.Z)) *
                       (std::abs(p.X1) + std::abs(p.Y1) + std::abs(p.Z1)) * (1 + k.R / rho);
    if (std::abs(psi) <= 16 * kEps * mag) {
      *th = t;
      return std::abs(wrap_pi(t - th0)) < 1e-2;
    }
    if (dpsi == 0) return false;
    double step = -psi / dpsi;
    step = std::clamp(step, -1e-2, 1e-2);
    t += step;
    if (std::abs(step) <= 1e-16) {
      *th = t;
      return std::abs(psi) <= 1e-9 * std::max(mag, 1e-300) && std::abs(wrap_pi(t - th0)) < 1e-2;
    }
  }
  return false;
}

// Points where b crosses a's axis: minima of ρ^2 (roots of Qp, a quartic in t)
// where ρ vanishes to rounding.
int axis_crossings(const PairCoeffs& k, double* th_out, double* rho_min) {
  double th[16];
  const int n = rho2_critical_angles(k, th);
  int m = 0;
  *rho_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    // Newton on Qp = (ρ^2)'/2 polishes the minimum of ρ^2.
    double t = th[i];
    for (int it = 0; it < 8; ++it) {
      const Pt p = at(k, t);
      const double Qp = p.X * p.X1 + p.Y * p.Y1;
      const double Qp1 = p.X1 * p.X1 + p.Y1 * p.Y1 + p.X * p.X2 + p.Y * p.Y2;
      if (Qp1 <= 0) break;
      t -= Qp / Qp1;
    }
    const Pt p = at(k, t);
    const double rho = std::sqrt(p.X * p.X + p.Y * p.Y);
    *rho_min = std::min(*rho_min, rho);
    // ρ at scale ~1 after frame rounding: a few ε; 64ε with margin.
    if (rho <= 64 * kEps) th_out[m++] = t;
  }
  return m;
}

Vec3 on_b(const CircleFrame& b, double th) {
  return b.center + b.radius * (std::cos(th) * b.u + std::sin(th) * b.v);
}

// Angle windows of b (θ in b's frame) outside which no needed line ends:
// every point of b is at least max_len from circle a there, or the caller's
// arc test rules the arc out. b is cut into 8 arcs, each held by a ball around
// its chord's midpoint; an arc is dropped when its ball is max_len or more
// from a (point-circle distance, closed form) or fails the test, and cut in 4
// and tested again otherwise. Writes [lo, hi] pairs (merged, increasing),
// returns their count, and the least distance bound over what was dropped for
// distance (+inf when nothing).
int near_windows(const CircleFrame& a, const CircleFrame& b, double max_len, const BinormalArcTest* test, double* win,
                 double* dropped_lb) {
  *dropped_lb = std::numeric_limits<double>::infinity();
  // Rounding of the bound: a few ulps of the coordinates involved.
  const double margin = 64 * kEps * (a.center.cwiseAbs().maxCoeff() + b.center.cwiseAbs().maxCoeff() + a.radius + b.radius);
  // Arc [lo, lo + w] -> bound (+inf when the test drops it).
  auto arc_bound = [&](double lo, double w) {
    const double th = lo + 0.5 * w, half = 0.5 * w;
    const Vec3 m = b.center + b.radius * std::cos(half) * (std::cos(th) * b.u + std::sin(th) * b.v);
    const double r = b.radius * std::sin(half);
    const Vec3 d = m - a.center;
    const double h = d.dot(a.n);
    const double rho = std::sqrt(std::max(0.0, d.squaredNorm() - h * h));
    const double lb = std::sqrt(h * h + (rho - a.radius) * (rho - a.radius)) - r - margin;
    if (lb < max_len && test && test->keep && !test->keep(test->ctx, m, r)) return std::numeric_limits<double>::infinity();
    return lb;
  };
  auto dropped = [&](double lb) {
    if (lb < max_len) return false;
    if (lb < std::numeric_limits<double>::infinity()) *dropped_lb = std::min(*dropped_lb, lb);
    return true;
  };
  int nw = 0;
  const double w1 = 2 * kPi / 8, w2 = w1 / 4;
  for (int i = 0; i < 8; ++i) {
    if (dropped(arc_bound(-kPi + i * w1, w1))) continue;
    for (int j = 0; j < 4; ++j) {
      const double lo = -kPi + i * w1 + j * w2;
      if (dropped(arc_bound(lo, w2))) continue;
      if (nw > 0 && std::abs(win[2 * nw - 1] - lo) <= 1e-12) win[2 * nw - 1] = lo + w2;  // contiguous: merge
      else {
        win[2 * nw] = lo;
        win[2 * nw + 1] = lo + w2;
        ++nw;
      }
    }
  }
  // The last window may continue the first across the seam at ±π.
  if (nw > 1 && win[0] == -kPi && std::abs(win[2 * nw - 1] - kPi) <= 1e-12) {
    win[0] = win[2 * nw - 2] - 2 * kPi;
    --nw;
  }
  return nw;
}

// The binormal lines of a and b found on one parameterisation (θ on b; with
// max_len finite only in b's near windows, *dropped_lb bounding what is left
// out). *ill is set when its polynomial cannot be trusted to show every root.
std::vector<Line> lines_one_order(const Circle3& a_in, const Circle3& b_in, bool* infinite, double max_len,
                                  double* dropped_lb, const BinormalArcTest* test, bool* ill) {
  if (dropped_lb) *dropped_lb = std::numeric_limits<double>::infinity();
  *infinite = false;
  *ill = false;
  std::vector<Line> out;
  const double sigma = circle_pair_sigma(a_in, b_in);
  const CircleFrame a = make_frame(a_in), b = make_frame(b_in);
  const double contact = 64 * kEps;  // scaled: a line this short is a contact point
  if (b.radius == 0) {
    // Named: b a point Q. Lines to a's near and far points, or (Q on a's axis) a cone.
    const Vec3 d = (b.center - a.center) * sigma;
    const double h = d.dot(a.n), px = d.dot(a.u), py = d.dot(a.v);
    const double rho = std::sqrt(px * px + py * py), R = a.radius * sigma;
    if (R == 0 || rho <= 8 * kEps * d.cwiseAbs().maxCoeff()) {
      // Two points (R = 0): the segment between them, |d|, not its axial part;
      // Q on a's axis: sqrt(h^2 + R^2) up to the rounding-sized rho.
      const double e = rho - R;
      const double len = std::sqrt(h * h + e * e);
      if (len > contact) out.push_back({0, a.center + a.radius * a.u, len / sigma});
      return out;
    }
    const Vec3 dir = (px * a.u + py * a.v) / rho;
    for (double sg : {1.0, -1.0}) {
      const double e = rho - sg * R;
      const double len = std::sqrt(h * h + e * e);
      if (len > contact) out.push_back({0, a.center + sg * a.radius * dir, len / sigma});
    }
    return out;
  }
  const PairCoeffs k = make_coeffs(b, a, sigma);
  if (k.R == 0) {
    // Named: a a point. Critical points of |P - C_a|^2 = a0 + a1 cosθ + b1 sinθ;
    // C_a on b's axis makes it constant.
    if (std::hypot(k.a1, k.b1) <= 64 * kEps) {
      *infinite = true;
      return out;
    }
    const double th0 = std::atan2(k.b1, k.a1);
    for (double th : {th0, wrap_pi(th0 + kPi)}) {
      const double len = std::sqrt(std::max(0.0, k.a0 + k.a1 * std::cos(th) + k.b1 * std::sin(th)));
      if (len > contact) out.push_back({th, a.center, len / sigma});
    }
    return out;
  }
  // The binormal polynomial Φ in t, with a bound on its terms (*mag) and on the
  // rounding error of its coefficients (*err, summed over them).
  // Why *err: Φ = ρ²L² - R²Qp² cancels to far below its terms when one branch
  // is nearly degenerate for every point of b (b's centre nearly on a with b
  // in a meridian plane of a, or the swapped order: the foot on a barely moves),
  // and near a mirror symmetry its roots are double; such a touching root is
  // lost when it is judged against the size of the cancelled coefficients.
  // Each coefficient is a sum of products of the t-form coefficients with ~16
  // roundings on the way; over all coefficients the terms sum to the product of
  // the factors' 1-norms.
  auto phi_poly = [](const PairCoeffs& r, double* phi, double* mag, double* err) {
    double X[3], Y[3], Xd[3], Yd[3], L[3];
    trig1_to_t(r.x0, r.x1, r.x2, X);
    trig1_to_t(r.y0, r.y1, r.y2, Y);
    trig1_to_t(0, r.x2, -r.x1, Xd);
    trig1_to_t(0, r.y2, -r.y1, Yd);
    trig1_to_t(0, 0.5 * r.b1, -0.5 * r.a1, L);  // L = (|Δ|^2)'/2
    double rho2[5], t1[5], Qp[5], L2[5], A[9], B[9];
    poly_mul(X, 2, X, 2, rho2);
    poly_mul(Y, 2, Y, 2, t1);
    for (int i = 0; i <= 4; ++i) rho2[i] += t1[i];
    poly_mul(X, 2, Xd, 2, Qp);
    poly_mul(Y, 2, Yd, 2, t1);
    for (int i = 0; i <= 4; ++i) Qp[i] += t1[i];
    poly_mul(L, 2, L, 2, L2);
    poly_mul(rho2, 4, L2, 4, A);
    poly_mul(Qp, 4, Qp, 4, B);
    double m = 0;
    for (int i = 0; i <= 8; ++i) {
      phi[i] = A[i] - r.R * r.R * B[i];
      m += std::abs(A[i]) + r.R * r.R * std::abs(B[i]);
    }
    *mag = m;
    auto n1 = [](const double* p) { return std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]); };
    const double nX = n1(X), nY = n1(Y), nL = n1(L);
    const double terms = (nX * nX + nY * nY) * nL * nL + r.R * r.R * std::pow(nX * n1(Xd) + nY * n1(Yd), 2);
    *err = 32 * kEps * terms;
  };
  double phi[9], mag, err;
  phi_poly(k, phi, &mag, &err);
  double big = 0;
  for (double c : phi) big = std::max(big, std::abs(c));
  if (big <= 256 * kEps * mag) {
    // Named: Φ ≡ 0 (coaxial, Villarceau, meridian): every point of b is critical
    // for the near or the far branch. The other branch may still have isolated
    // lines (a meridian circle's lines to the far foot): the other order finds them.
    *infinite = true;
    *ill = true;
    return out;
  }
  double sum_phi = 0;
  for (double c : phi) sum_phi += std::abs(c);
  // Φ = ρ²·ψ₊·ψ₋ (ρ: distance from b's point to a's axis, ψ±: the branches'
  // derivatives). A branch that nearly vanishes along all of b (b nearly a
  // meridian circle of a, or a's foot nearly fixed) shrinks every coefficient
  // far below its terms; b passing near a's axis shrinks Φ by ρ² near the
  // roots there. Either way a root of the other branch can sink into the
  // rounding. kIll: a thousandth, where the worst misses measured began
  // (tilts of 1e-3 from a meridian plane, axis passes of 1e-2 of the scale).
  constexpr double kIll = 1e-3;
  if (sum_phi < kIll * err / (32 * kEps)) *ill = true;
  constexpr int kCap = 640;  // 16 windows at most, 36 entries each (two charts, wrapped)
  double th[kCap];
  int n = -1;
  if ((std::isfinite(max_len) || test) && dropped_lb) {
    double win[2 * 32], dlb;
    const int nw = near_windows(a, b, max_len, test, win, &dlb);
    *dropped_lb = dlb;
    n = 0;
    for (int w = 0; w < nw && n >= 0; ++w) {
      const int m = trig_poly_roots_window(phi, 8, win[2 * w], win[2 * w + 1], th + n, kCap - n, err);
      n = m < 0 ? -1 : n + m;
    }
    if (n < 0) *dropped_lb = std::numeric_limits<double>::infinity();  // whole circle below
  }
  if (n < 0) n = trig_poly_roots(phi, 8, th, err);
  for (int i = 0; i < n; ++i) {
    for (double sg : {1.0, -1.0}) {
      double t = th[i];
      if (!polish_branch(k, sg, &t)) continue;
      const Pt p = at(k, t);
      const double rho = std::sqrt(p.X * p.X + p.Y * p.Y);
      const double e = rho - sg * k.R;
      const double len = std::sqrt(p.Z * p.Z + e * e);
      if (len <= contact) continue;
      const Vec3 dir = (p.X * a.u + p.Y * a.v) / rho;
      out.push_back({wrap_pi(t), a.center + sg * a.radius * dir, len / sigma});
    }
  }
  // Named: b crosses a's axis at Q. The lines from Q to the points of a in the
  // plane through Q normal to b's tangent T: X'cosφ + Y'sinφ = Z·Z'/R.
  double ax[8], rho_min;
  const int na = axis_crossings(k, ax, &rho_min);
  if (rho_min < 10 * kIll) *ill = true;
  for (int i = 0; i < na; ++i) {
    const Pt p = at(k, ax[i]);
    const double tau = std::hypot(p.X1, p.Y1);
    const double len = std::sqrt(p.Z * p.Z + k.R * k.R);
    if (tau <= 64 * kEps) {
      // T along a's axis: every point of a qualifies when Q = C_a (Z = 0), none otherwise.
      if (std::abs(p.Z) <= 64 * kEps) out.push_back({wrap_pi(ax[i]), a.center + a.radius * a.u, len / sigma});
      continue;
    }
    const double ratio = p.Z * p.Z1 / (k.R * tau);
    if (std::abs(ratio) > 1 + 64 * kEps) continue;
    const double psi0 = std::atan2(p.Y1, p.X1), w = std::acos(std::clamp(ratio, -1.0, 1.0));
    for (double phi_a : {psi0 + w, psi0 - w}) {
      const Vec3 dir = std::cos(phi_a) * a.u + std::sin(phi_a) * a.v;
      out.push_back({wrap_pi(ax[i]), a.center + a.radius * dir, len / sigma});
    }
  }
  return out;
}

// All binormal lines of a and b, or (max_len finite) at least every one
// shorter than max_len: roots are then sought only in b's near windows, and
// *dropped_lb bounds the length of any line left out from below.
// A binormal line of (a, b) is one of (b, a): when the polynomial on b is ill
// conditioned (see lines_one_order) the lines found on a are added. Whole
// circle there (extra lines are harmless to callers of the _within form).
std::vector<Line> all_lines(const Circle3& a_in, const Circle3& b_in, bool* infinite,
                            double max_len = std::numeric_limits<double>::infinity(),
                            double* dropped_lb = nullptr, const BinormalArcTest* test = nullptr) {
  bool ill = false;
  std::vector<Line> out = lines_one_order(a_in, b_in, infinite, max_len, dropped_lb, test, &ill);
  const CircleFrame a = make_frame(a_in), b = make_frame(b_in);
  if (ill && a_in.radius > 0 && b_in.radius > 0) {
    bool inf2 = false, ill2 = false;
    const std::vector<Line> sw =
        lines_one_order(b_in, a_in, &inf2, std::numeric_limits<double>::infinity(), nullptr, nullptr, &ill2);
    for (const Line& l : sw) {
      // l.th is on a, l.on_a on b.
      const Vec3 d = l.on_a - b.center;
      out.push_back({std::atan2(d.dot(b.v), d.dot(b.u)), on_b(a, l.th), l.dist});
    }
  }
  // One entry per line: roots found twice (both charts, both Φ candidates of a
  // double root, both orders) polish to the same θ and the same point of a.
  std::sort(out.begin(), out.end(), [](const Line& x, const Line& y) { return x.th < y.th; });
  std::vector<Line> uniq;
  const double same_th = 1e-9;  // radians: below what a polished simple root can drift
  for (const Line& l : out) {
    bool dup = false;
    for (const Line& u : uniq)
      if (std::abs(wrap_pi(l.th - u.th)) <= same_th && (l.on_a - u.on_a).norm() <= 1e-9 * (a.radius + 1e-300)) dup = true;
    if (!dup) uniq.push_back(l);
  }
  return uniq;
}

std::vector<CircleBinormal> to_public(const CircleFrame& b, const std::vector<Line>& lines) {
  std::vector<CircleBinormal> v;
  v.reserve(lines.size());
  for (const Line& l : lines) v.push_back({l.on_a, on_b(b, l.th), l.dist});
  return v;
}

}  // namespace

std::vector<CircleBinormal> circle3_circle3_binormal_lines(const Circle3& a, const Circle3& b,
                                                           bool* infinitely_many) {
  bool inf = false;
  const auto lines = all_lines(a, b, &inf);
  if (infinitely_many) *infinitely_many = inf;
  return to_public(make_frame(b), lines);
}

std::vector<CircleBinormal> circle3_circle3_binormal_lines_within(const Circle3& a, const Circle3& b, double max_len,
                                                                  bool* infinitely_many, double* dropped_lb,
                                                                  const BinormalArcTest* arc_test) {
  bool inf = false;
  double dlb = std::numeric_limits<double>::infinity();
  const auto lines = all_lines(a, b, &inf, max_len, &dlb, arc_test);
  if (infinitely_many) *infinitely_many = inf;
  if (dropped_lb) *dropped_lb = inf ? std::numeric_limits<double>::infinity() : dlb;
  return to_public(make_frame(b), lines);
}

std::vector<CircleBinormal> circle3_circle3_binormals(const Circle3& a, const Circle3& b,
                                                      bool* infinitely_many) {
  // One definition with the distance kernel: closest pairs that form a
  // continuum (decided there to rounding, e.g. coaxial circles whose rotated
  // doubles left the polynomial a few ulps from zero) whose point on b is off
  // a's axis (so it has one nearest point on a) move along b: a continuum of
  // lines. (A closest point of b on a's axis has finitely many lines: those in
  // the plane normal to b there.) A point b on a's axis sees all of a: a cone.
  bool inf = false;
  const Circle3Circle3Result d = circle3_circle3_distance(a, b);
  const Vec3 n = unit_normal(a.normal);
  const double scale = std::max({a.radius, b.radius, (a.center - b.center).norm()});
  if (d.status == CircleCircleStatus::infinitely_many && a.radius > 0 && b.radius > 0)
    inf = (d.point_b - a.center).cross(n).norm() > 1e-9 * scale;
  if (b.radius == 0 && a.radius > 0 && (b.center - a.center).cross(n).norm() <= 1e-9 * scale) inf = true;
  const auto lines = inf ? std::vector<Line>{} : all_lines(a, b, &inf);
  if (infinitely_many) *infinitely_many = inf;
  if (inf) return {};
  if (a.radius == 0 || b.radius == 0) return to_public(make_frame(b), lines);
  // One entry per line, except that roots of one branch the rounding cannot
  // separate are one line: consecutive lines of the same branch (near: the foot
  // on a on Q's side of a's axis; far: opposite) between which the branch
  // derivative ψ stays within its rounding at every sample. On nearly coaxial
  // or nearly tangent circles ψ is that flat over a whole arc and the solver
  // polishes a root anywhere in it; the exact engine sees the one (or two
  // close) roots of the given doubles there.
  const double sigma = circle_pair_sigma(a, b);
  const CircleFrame fa = make_frame(a), fb = make_frame(b);
  const PairCoeffs k = make_coeffs(fb, fa, sigma);
  auto branch = [&](const Line& l) {
    const Vec3 q = on_b(fb, l.th) - a.center, pa = l.on_a - a.center;
    const Vec3 qp = q - q.dot(fa.n) * fa.n;
    if (qp.norm() <= 64 * kEps * scale) return 0;  // Q on a's axis: lines of a cone, kept apart
    return qp.dot(pa) > 0 ? 1 : -1;
  };
  // ψσ at t, its rounding (as polish_branch judges it) and its slope.
  auto psi_at = [&](int sg, double t, double* noise, double* slope) {
    const Pt p = at(k, t);
    const double rho = std::sqrt(p.X * p.X + p.Y * p.Y);
    const double Qp = p.X * p.X1 + p.Y * p.Y1;
    const double L1 = p.X1 * p.X1 + p.Y1 * p.Y1 + p.Z1 * p.Z1 + p.X * p.X2 + p.Y * p.Y2 + p.Z * p.Z2;
    const double Qp1 = p.X1 * p.X1 + p.Y1 * p.Y1 + p.X * p.X2 + p.Y * p.Y2;
    *noise = 16 * kEps * (std::abs(p.X) + std::abs(p.Y) + std::abs(p.Z)) *
             (std::abs(p.X1) + std::abs(p.Y1) + std::abs(p.Z1)) * (1 + k.R / rho);
    *slope = L1 - sg * k.R * (Qp1 / rho - Qp * Qp / (rho * rho * rho));
    return Qp + p.Z * p.Z1 - sg * k.R * Qp / rho;
  };
  auto flat = [&](int sg, double t) {
    double noise, slope;
    return std::abs(psi_at(sg, t, &noise, &slope)) <= noise;
  };
  // How far a root polished to rounding may sit from the true one: the
  // rounding over the slope (a double root: the flat zone around it).
  auto spread = [&](int sg, double t) {
    double noise, slope;
    psi_at(sg, t, &noise, &slope);
    return std::min(0.25, noise / std::abs(slope));
  };
  std::vector<Line> kept;
  for (int sg : {1, -1, 0}) {
    std::vector<Line> br;
    for (const Line& l : lines)
      if (branch(l) == sg) br.push_back(l);  // sorted by θ
    if (sg == 0 || br.size() < 2) {
      kept.insert(kept.end(), br.begin(), br.end());
      continue;
    }
    auto joined = [&](const Line& l, const Line& r) {  // r after l going up in θ (mod 2π)
      double gap = r.th - l.th;
      if (gap <= 0) gap += 2 * kPi;
      if (gap > 0.25) return false;  // far apart: never one root
      if (gap <= 4 * (spread(sg, l.th) + spread(sg, r.th))) return true;
      constexpr int kSamples = 8;
      for (int i = 1; i < kSamples; ++i)
        if (!flat(sg, l.th + gap * i / kSamples)) return false;
      return true;
    };
    // Start a cluster where the previous line (cyclically) is not joined.
    std::size_t s0 = 0;
    while (s0 < br.size() && joined(br[(s0 + br.size() - 1) % br.size()], br[s0])) ++s0;
    if (s0 == br.size()) {  // one cluster around the whole circle
      kept.push_back(br[0]);
      continue;
    }
    for (std::size_t i = 0; i < br.size(); ++i) {
      const std::size_t j = (s0 + i) % br.size();
      if (i == 0 || !joined(br[(j + br.size() - 1) % br.size()], br[j])) kept.push_back(br[j]);
    }
  }
  std::sort(kept.begin(), kept.end(), [](const Line& x, const Line& y) { return x.th < y.th; });
  return to_public(fb, kept);
}

}  // namespace revdist
