// Normal lines of conical patches against circles and cones (see the header).
//
// Circle against cone line. Circle C: P(θ) = C + r(u cosθ + v sinθ); in K's
// frame z(θ) and |P - o|^2 are trig polynomials of degree 1, so
// q = ρ^2 = |P - o|^2 - z^2 has degree 2. h = n_r ρ + n_z z is critical where
// n_r q' + 2 n_z z' ρ = 0; squaring, F = n_r^2 q'^2 - 4 n_z^2 z'^2 q = 0, a trig
// polynomial of degree 4: degree 8 in t = tan(θ/2). Squaring adds the critical
// points of the mirror cone (−n_r): harmless extra points of C.
//
// Cone against cone. A normal line of a cone with n_r != 0 lies in a meridian
// plane and meets the axis at the angle of the cone's normal: through
// Q_A = o_A + λ a with (d . a)^2 = n_zA^2 |d|^2, d = Q_B - Q_A, Q_B = o_B + μ b,
// and (d . b)^2 = n_zB^2 |d|^2. Two quadrics in (λ, μ); eliminating λ leaves a
// quartic in μ (resultant of two quadratics).
//
// Output counts (the capacities in the header). poly_roots_in reports at most
// n + 1 roots of a degree-n polynomial on an interval (n monotone pieces
// between critical points, plus an exact zero at the right end), so
// trig_poly_roots reports at most 2 (n + 1) angles over its two charts: 18
// for degree 8, 10 for degree 4. circle_cone_critical: 18 when h varies on C;
// when h is constant, 1 + 10 (extremes of ρ_K, degree 4) + 2 · 10 (ρ_K equal
// to either end's radius, degree 4) = 31 <= kCircleConeCriticalMax.
// cone_cone_normals: two conics in (λ, μ) share at most 4 points (Bezout) when
// the system is not degenerate; each gives one line, whose feet are at most
// 2 on either cone (both sides of the axis, for a cylinder), so at most 4
// pairs: 16 in all. The code can report more only in near-degenerate systems
// (the quartic's n + 1, a λ double root emitting both roots, lines through a
// point where the axes meet: 4 directions of 4 pairs each, the grid of 36
// Newton starts when the resultant vanishes); there it keeps
// kConeConeNormalsMax pairs and reports the rest as a degenerate system.
#include "fast/cone_normals.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "fast/circle_internal.h"

namespace revdist {

namespace {

using namespace circle_detail;

// Small dense polynomials (coefficient i of t^i).
struct Poly {
  double c[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  int n = 0;
};

Poly mul(const Poly& a, const Poly& b) {
  Poly r;
  r.n = a.n + b.n;
  poly_mul(a.c, a.n, b.c, b.n, r.c);
  return r;
}
Poly mul_abs(const Poly& a, const Poly& b) {
  Poly x = a, y = b;
  for (int i = 0; i <= x.n; ++i) x.c[i] = std::abs(x.c[i]);
  for (int i = 0; i <= y.n; ++i) y.c[i] = std::abs(y.c[i]);
  return mul(x, y);
}
Poly lin(double a, double b, double c, double s) {  // s * (a + b t + c t^2)
  Poly p;
  p.n = 2;
  p.c[0] = s * a;
  p.c[1] = s * b;
  p.c[2] = s * c;
  return p;
}
Poly axpy(double alpha, const Poly& x, double beta, const Poly& y) {
  Poly r;
  r.n = std::max(x.n, y.n);
  for (int i = 0; i <= r.n; ++i) r.c[i] = alpha * (i <= x.n ? x.c[i] : 0) + beta * (i <= y.n ? y.c[i] : 0);
  return r;
}
Poly trig1(double q0, double q1, double q2) {
  Poly p;
  p.n = 2;
  trig1_to_t(q0, q1, q2, p.c);
  return p;
}
double max_abs(const Poly& p) {
  double m = 0;
  for (int i = 0; i <= p.n; ++i) m = std::max(m, std::abs(p.c[i]));
  return m;
}
double sum_abs(const Poly& p) {
  double m = 0;
  for (int i = 0; i <= p.n; ++i) m += std::abs(p.c[i]);
  return m;
}

// Circle C written in the frame of patch K's axis, lengths scaled by sigma:
// z(θ) and q(θ) = ρ^2 as polynomials in t = tan(θ/2), times (1+t^2) and (1+t^2)^2.
struct CircleInAxisFrame {
  CircleFrame f;
  double sigma;
  Poly Z, Zp, Q, Q1, one;  // z, z', q, q' (t-forms), 1 + t^2
  Poly Qa, Q1a;            // |.| versions for rounding estimates
  Vec3 point(double th, const Circle3& C) const {
    return C.center + C.radius * (f.u * std::cos(th) + f.v * std::sin(th));
  }
};

CircleInAxisFrame circle_in_axis_frame(const Circle3& C, const Patch& K) {
  CircleInAxisFrame k;
  k.f = make_frame(C);
  const Vec3 D0 = C.center - K.o;
  k.sigma = pow2_inverse(std::max(D0.cwiseAbs().maxCoeff(), C.radius));
  const Vec3 D = D0 * k.sigma;
  const double r = C.radius * k.sigma;
  const Vec3 U = k.f.u * r, V = k.f.v * r;
  const double z0 = D.dot(K.a), z1 = U.dot(K.a), z2 = V.dot(K.a);
  const double d0 = D.squaredNorm() + r * r, d1 = 2 * D.dot(U), d2 = 2 * D.dot(V);
  k.Z = trig1(z0, z1, z2);
  k.Zp = trig1(0, z2, -z1);
  const Poly Dt = trig1(d0, d1, d2), Dp = trig1(0, d2, -d1);
  k.one = lin(1, 0, 1, 1);
  k.Q = axpy(1, mul(Dt, k.one), -1, mul(k.Z, k.Z));
  k.Q1 = axpy(1, mul(Dp, k.one), -2, mul(k.Z, k.Zp));
  k.Qa = axpy(1, mul_abs(Dt, k.one), 1, mul_abs(k.Z, k.Z));
  k.Q1a = axpy(1, mul_abs(Dp, k.one), 2, mul_abs(k.Z, k.Zp));
  return k;
}

// Newton on the unsquared condition h'(θ) = s n_r ρ' + n_z z' = 0 for the
// branch s = +1 (the generator in P's half-plane) or -1 (its mirror) that
// vanishes at th. Squaring made double roots of simple ones (for a cylinder,
// n_z = 0, every root is double), which a root finder only places to about
// sqrt(ε); the distance there would be off at second order.
double polish_circle_cone(const Circle3& C, const CircleFrame& f, const Patch& K, double th) {
  const Vec3 D = C.center - K.o;
  const Vec3 U = C.radius * f.u, V = C.radius * f.v;
  const double nr = K.n.x(), nz = K.n.y();
  auto eval = [&](double t, double s, double* d1, double* d2) {
    const double c = std::cos(t), sn = std::sin(t);
    const Vec3 X = D + U * c + V * sn, X1 = V * c - U * sn, X2 = -(U * c + V * sn);
    const double z = X.dot(K.a), z1 = X1.dot(K.a), z2 = X2.dot(K.a);
    const double q = X.squaredNorm() - z * z;
    const double q1 = 2 * X.dot(X1) - 2 * z * z1;
    const double q2 = 2 * (X1.squaredNorm() + X.dot(X2)) - 2 * (z1 * z1 + z * z2);
    const double rho = std::sqrt(std::max(q, 0.0));
    if (!(rho > 0)) return false;
    const double r1 = q1 / (2 * rho), r2 = (q2 / 2 - r1 * r1) / rho;
    *d1 = s * nr * r1 + nz * z1;
    *d2 = s * nr * r2 + nz * z2;
    return true;
  };
  double s = 1, best = std::numeric_limits<double>::infinity();
  for (double side : {1.0, -1.0}) {
    double d1, d2;
    if (eval(th, side, &d1, &d2) && std::abs(d1) < best) {
      best = std::abs(d1);
      s = side;
    }
  }
  double t = th;
  for (int it = 0; it < 8; ++it) {
    double d1, d2;
    if (!eval(t, s, &d1, &d2) || d2 == 0) break;
    const double step = d1 / d2;
    if (!(std::abs(step) < 0.1)) break;  // not converging to this root: keep the last point
    double n1, n2;
    if (!eval(t - step, s, &n1, &n2) || std::abs(n1) > std::abs(d1)) break;
    t -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return t;
}

}  // namespace

int circle_cone_critical(const Circle3& C, const Patch& K, Vec3* out, bool* degenerate) {
  *degenerate = false;
  if (C.radius == 0) {
    out[0] = C.center;
    return 1;
  }
  const CircleInAxisFrame k = circle_in_axis_frame(C, K);
  const Poly& Q = k.Q;
  const Poly& Q1 = k.Q1;
  const Poly& one = k.one;
  const Poly& Qa = k.Qa;
  const double sigma = k.sigma;
  const double nr2 = K.n.x() * K.n.x(), nz2 = K.n.y() * K.n.y();
  // h' = n_r q' / (2 rho) + n_z z'. A flat annulus (n_r = 0) needs only z' = 0
  // and a cylinder (n_z = 0) only q' = 0: solving those directly avoids the
  // squared form, whose roots would all be double there.
  Poly F, Fa;
  if (K.n.x() == 0) {
    F = k.Zp;
    Fa = mul_abs(k.Zp, Poly{{1}, 0});
  } else if (K.n.y() == 0) {
    F = Q1;
    Fa = k.Q1a;
  } else {
    F = axpy(nr2, mul(Q1, Q1), -4 * nz2, mul(mul(k.Zp, k.Zp), Q));
    // Rounding of the products: a few ε of the absolute-value products.
    Fa = axpy(nr2, mul(k.Q1a, k.Q1a), 4 * nz2, mul(mul_abs(k.Zp, k.Zp), Qa));
  }
  auto point = [&](double t) { return k.point(t, C); };
  double th[18];  // two root charts of a degree-8 polynomial: 2 (8 + 1)
  int n = 0;
  if (max_abs(F) > 256 * kEps * max_abs(Fa)) {
    n = trig_poly_roots(F.c, F.n, th);
    for (int i = 0; i < n; ++i) out[i] = point(polish_circle_cone(C, k.f, K, th[i]));
    return n;
  }
  // h is constant on C: the ends of the arcs of C whose feet fall in the segment.
  *degenerate = true;
  int m = 0;
  out[m++] = point(0.0);
  if (max_abs(Q1) > 256 * kEps * max_abs(k.Q1a)) {
    n = trig_poly_roots(Q1.c, 4, th);
    for (int i = 0; i < n; ++i) out[m++] = point(th[i]);
  }
  const Poly one2 = mul(one, one);
  for (const Vec2& q : {K.p0, K.p1}) {
    const double rr = q.x() * sigma;
    const Poly G = axpy(1, Q, -rr * rr, one2);
    if (max_abs(G) <= 256 * kEps * (max_abs(Qa) + rr * rr)) continue;
    n = trig_poly_roots(G.c, 4, th);
    for (int i = 0; i < n; ++i) out[m++] = point(th[i]);
  }
  return m;
}

namespace {

// Where the line through axis point Q (of straight patch P) with direction d
// meets P's cone line at a point where it is normal to the cone. Returns the
// count (0..2).
int normal_feet(const Patch& P, const Vec3& Q, const Vec3& d, Vec3* out) {
  const double zq = (Q - P.o).dot(P.a);
  const double da = d.dot(P.a);
  const Vec3 dh = d - da * P.a;
  const double h = dh.norm();
  const double len = d.norm();
  if (!(h > 0) || !(len > 0)) return 0;
  int k = 0;
  for (int side : {1, -1}) {
    // Points Q + t d with side * t >= 0 have local coordinates (|t| h, zq + t da):
    // in the half-plane of side * dh the line's local direction is (side h, da).
    const double den = P.n.x() * side * h + P.n.y() * da;
    if (den == 0) continue;
    const double t = (P.off - P.n.y() * zq) / den;
    if (side * t < 0) continue;
    // Normal to the cone here: the local direction is parallel to n.
    const double cosang = std::abs(den) / len;
    if (cosang < 1 - 1e-6) continue;
    out[k++] = Q + t * d;
  }
  return k;
}

// Pairs (x on A's cone, y on B's cone) joined by a common normal through Q_A, Q_B.
// When the line is normal to one cone but meets the other only where r < 0, the
// missing foot is NaN: the point found still matters for the sign tests.
int pair_feet(const Patch& A, const Patch& B, const Vec3& QA, const Vec3& QB, const Vec3& d, Vec3* xo, Vec3* yo) {
  Vec3 xs[2], ys[2];
  const int nx = normal_feet(A, QA, d, xs);
  const int ny = normal_feet(B, QB, d, ys);
  const Vec3 none = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  int k = 0;
  for (int i = 0; i < std::max(nx, 1); ++i)
    for (int j = 0; j < std::max(ny, 1); ++j) {
      if (i >= nx && j >= ny) continue;
      xo[k] = i < nx ? xs[i] : none;
      yo[k] = j < ny ? ys[j] : none;
      ++k;
    }
  return k;
}

// Newton on the unsquared angle conditions d . a = s1 n_zA |d|, d . b =
// s2 n_zB |d| (d = w + μ b - λ a, scaled units), signs taken from the
// approximate root. The squared system has double roots (every one for two
// cylinders), so the resultant's roots are only good to about sqrt(ε).
// Returns |residual| at the end (scaled units). Signs s1, s2 in {-1, 1}, or 0
// to take them from the starting point.
double polish_cone_cone(const Vec3& w, const Vec3& a, const Vec3& b, double nzA, double nzB, double* lam, double* mu,
                        double s1 = 0, double s2 = 0) {
  const double c = a.dot(b);
  struct State {
    double da, db, len;  // d . a, d . b, |d|
  };
  auto state = [&](double l, double m) {
    const Vec3 d = w + m * b - l * a;
    return State{d.dot(a), d.dot(b), d.norm()};
  };
  State st = state(*lam, *mu);
  if (!(st.len > 0)) return std::numeric_limits<double>::infinity();
  if (s1 == 0) s1 = st.da * nzA >= 0 ? 1 : -1;
  if (s2 == 0) s2 = st.db * nzB >= 0 ? 1 : -1;
  auto residual = [&](const State& x) {
    return Vec2(x.da - s1 * nzA * x.len, x.db - s2 * nzB * x.len);
  };
  double l = *lam, m = *mu;
  Vec2 f = residual(st);
  for (int it = 0; it < 30; ++it) {
    const double j11 = -1 + s1 * nzA * st.da / st.len, j12 = c - s1 * nzA * st.db / st.len;
    const double j21 = -c + s2 * nzB * st.da / st.len, j22 = 1 - s2 * nzB * st.db / st.len;
    const double det = j11 * j22 - j12 * j21;
    if (det == 0) break;
    const double dl = (f.x() * j22 - f.y() * j12) / det, dm = (j11 * f.y() - j21 * f.x()) / det;
    const State next = state(l - dl, m - dm);
    if (!(next.len > 0)) break;
    const Vec2 g = residual(next);
    if (g.norm() > f.norm()) break;  // not converging: keep the last point
    l -= dl;
    m -= dm;
    st = next;
    f = g;
    if (std::abs(dl) + std::abs(dm) < 1e-16) break;
  }
  *lam = l;
  *mu = m;
  return f.norm();
}

}  // namespace

namespace {

std::atomic<std::uint64_t> g_cone_fallbacks{0};

// The count, and the fallback when candidates did not fit: a degenerate
// system, so the caller keeps the pair's bounds conservative.
int finish(int k, bool overflow, bool* degenerate) {
  if (overflow) {
    *degenerate = true;
    g_cone_fallbacks.fetch_add(1, std::memory_order_relaxed);
  }
  return k;
}

}  // namespace

std::uint64_t cone_normals_fallbacks() { return g_cone_fallbacks.load(std::memory_order_relaxed); }

int cone_cone_normals(const Patch& A, const Patch& B, Vec3* x_out, Vec3* y_out, bool* degenerate) {
  *degenerate = false;
  const double nrA = A.n.x(), nzA = A.n.y(), nrB = B.n.x(), nzB = B.n.y();
  // Flat annuli: normal lines parallel to the axis (families, see header).
  if (nrA == 0 || nrB == 0) return 0;
  const double c = A.a.dot(B.a);
  const Vec3 axb = A.a.cross(B.a);
  if (axb.squaredNorm() == 0) return 0;  // parallel axes: families, see header
  // Height range on B's axis of the normals of B's segment (z - r n_z / n_r at the ends).
  const double zb0 = B.p0.y() - B.p0.x() * nzB / nrB, zb1 = B.p1.y() - B.p1.x() * nzB / nrB;
  const Vec3 w0 = B.o - A.o;
  double size = std::max({w0.cwiseAbs().maxCoeff(), std::abs(zb0), std::abs(zb1), B.p0.norm(), B.p1.norm(),
                          A.p0.norm(), A.p1.norm()});
  const double sigma = pow2_inverse(size);
  const Vec3 w = w0 * sigma;
  const double wa = w.dot(A.a), wb = w.dot(B.a), ww = w.squaredNorm();
  const double nA2 = nzA * nzA, nB2 = nzB * nzB;
  // E1 = α2 λ^2 + α1 λ + α0, E2 = β2 λ^2 + β1 λ + β0, coefficients polynomials in μ.
  Poly a1, a0, b1, b0;
  const double al2 = 1 - nA2, be2 = c * c - nB2;
  a1.n = 1; a1.c[0] = -2 * al2 * wa; a1.c[1] = -2 * al2 * c;
  a0.n = 2; a0.c[0] = wa * wa - nA2 * ww; a0.c[1] = 2 * wa * c - nA2 * 2 * wb; a0.c[2] = c * c - nA2;
  b1.n = 1; b1.c[0] = -2 * c * wb + 2 * nB2 * wa; b1.c[1] = -2 * c + 2 * nB2 * c;
  b0.n = 2; b0.c[0] = wb * wb - nB2 * ww; b0.c[1] = 2 * wb - nB2 * 2 * wb; b0.c[2] = 1 - nB2;
  const Poly P = axpy(al2, b0, -be2, a0);   // α2 β0 - β2 α0   (λ^0 of α2 E2 - β2 E1)
  const Poly S = axpy(al2, b1, -be2, a1);   // α2 β1 - β2 α1   (λ^1)
  const Poly T = axpy(1, mul(a1, b0), -1, mul(b1, a0));  // α1 β0 - β1 α0
  const Poly Res = axpy(1, mul(P, P), -1, mul(S, T));
  const Poly Pa = axpy(std::abs(al2), mul_abs(b0, Poly{{1}, 0}), std::abs(be2), mul_abs(a0, Poly{{1}, 0}));
  const double mag = sum_abs(mul(Pa, Pa)) + sum_abs(mul_abs(S, T)) + 1e-300;
  int k = 0;
  bool overflow = false;
  // Pairs go through a buffer of 4 (pair_feet's most) so that none is written
  // past the caller's capacity; what does not fit marks the system degenerate.
  auto keep = [&](int n, const Vec3* xs, const Vec3* ys) {
    for (int i = 0; i < n; ++i) {
      if (k == kConeConeNormalsMax) {
        overflow = true;
        return;
      }
      x_out[k] = xs[i];
      y_out[k] = ys[i];
      ++k;
    }
  };
  // One common normal through Q_A = o_A + λ a and Q_B = o_B + μ b (scaled
  // units), polished on the unsquared conditions: its feet on both cones.
  auto emit = [&](double lam, double mu, bool polish) {
    Vec3 xs[4], ys[4];
    if (polish) polish_cone_cone(w, A.a, B.a, nzA, nzB, &lam, &mu);
    const Vec3 QA = A.o + (lam / sigma) * A.a;
    const Vec3 QB = B.o + (mu / sigma) * B.a;
    Vec3 d = QB - QA;
    if (d.norm() > 1e-12 / sigma) {
      keep(pair_feet(A, B, QA, QB, d, xs, ys), xs, ys);
      return;
    }
    // The axes meet here: lines through the meeting point at both normal angles.
    const Vec3 Qm = 0.5 * (QA + QB);
    const double det = 1 - c * c;
    for (int s1 : {1, -1})
      for (int g : {1, -1}) {
        const double ta = s1 * nzA, tb = nzB;  // d . a, d . b (d and -d are one line)
        const double al = (ta - c * tb) / det, be = (tb - c * ta) / det;
        const Vec3 base = al * A.a + be * B.a;
        const double rest = 1 - base.squaredNorm();
        if (rest < 0) continue;
        d = base + g * std::sqrt(rest / axb.squaredNorm()) * axb;
        keep(pair_feet(A, B, Qm, Qm, d, xs, ys), xs, ys);
        if (rest == 0) break;
      }
  };
  if (nzA == 0 && nzB == 0) {
    // Two cylinders: the common normals are the common perpendicular of the
    // axes (closed form; the squared system has only quadruple roots).
    const double det = 1 - c * c;
    emit((wa - c * wb) / det, (c * wa - wb) / det, false);
    return finish(k, overflow, degenerate);
  }
  const double margin = 1e-6;  // in scaled units: the range check on the feet decides
  const double lo = std::min(zb0, zb1) * sigma - margin, hi = std::max(zb0, zb1) * sigma + margin;
  if (max_abs(Res) <= 256 * kEps * mag) {
    // The resultant vanishes to rounding (axes nearly parallel, or a special
    // pose): Newton on the unsquared conditions from a grid of starts over
    // both axes' ranges and both normal orientations; only converged roots.
    const double za0 = A.p0.y() - A.p0.x() * nzA / nrA, za1 = A.p1.y() - A.p1.x() * nzA / nrA;
    double found[36][2];  // one per start at most
    int nf = 0;
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; j <= 2; ++j)
        for (double s1 : {1.0, -1.0})
          for (double s2 : {1.0, -1.0}) {
            double lam = (za0 + (za1 - za0) * i / 2) * sigma, mu = lo + (hi - lo) * j / 2;
            if (polish_cone_cone(w, A.a, B.a, nzA, nzB, &lam, &mu, s1, s2) > 1e-12) continue;
            bool dup = false;
            for (int f = 0; f < nf; ++f) dup = dup || (std::abs(found[f][0] - lam) + std::abs(found[f][1] - mu) < 1e-9);
            if (dup) continue;
            found[nf][0] = lam;
            found[nf][1] = mu;
            ++nf;
            emit(lam, mu, false);
          }
    return finish(k, overflow, degenerate);
  }
  double mus[8];  // poly_roots_in: at most n + 1 = 5
  const double tol = 64 * kEps * sum_abs(Res) * std::pow(std::max({1.0, std::abs(lo), std::abs(hi)}), 4);
  const int nm = poly_roots_in(Res.c, Res.n, lo, hi, tol, mus);
  for (int i = 0; i < nm; ++i) {
    const double mu = mus[i];
    const double s = poly_eval(S.c, S.n, mu);
    const double p = poly_eval(P.c, P.n, mu);
    const double e1a = al2, e1b = poly_eval(a1.c, 1, mu), e1c = poly_eval(a0.c, 2, mu);
    if (std::abs(s) > 1e-9 * (std::abs(p) + 1e-300) && std::abs(s) > 1e-14) {
      emit(-p / s, mu, true);
    } else {
      // λ is a double root direction of the pencil: solve E1 and keep both.
      const double disc = e1b * e1b - 4 * e1a * e1c;
      if (disc < 0 || e1a == 0) continue;
      const double sq = std::sqrt(disc);
      emit((-e1b + sq) / (2 * e1a), mu, true);
      emit((-e1b - sq) / (2 * e1a), mu, true);
    }
  }
  return finish(k, overflow, degenerate);
}

int line_surface_intersections(const Vec3& p, const Vec3& d, double s_max, const Patch& P, Vec3* out) {
  const Vec3 q = p - P.o;
  const double sigma = pow2_inverse(std::max({q.cwiseAbs().maxCoeff(), s_max, P.p0.norm(), P.p1.norm()}));
  const Vec3 qs = q * sigma;
  const double dd = d.squaredNorm();
  // z(s) = z0 + z1 s, rho^2(s) = A0 + A1 s + A2 s^2 (scaled s).
  const double z0 = qs.dot(P.a), z1 = d.dot(P.a);
  const double A0 = qs.squaredNorm() - z0 * z0, A1 = 2 * (qs.dot(d) - z0 * z1), A2 = dd - z1 * z1;
  double co[5] = {0, 0, 0, 0, 0};
  int deg;
  if (P.straight) {
    // n_r^2 rho^2 = (off - n_z z)^2.
    const double nr = P.n.x(), nz = P.n.y(), off = P.off * sigma;
    const double e0 = off - nz * z0, e1 = -nz * z1;
    co[0] = nr * nr * A0 - e0 * e0;
    co[1] = nr * nr * A1 - 2 * e0 * e1;
    co[2] = nr * nr * A2 - e1 * e1;
    deg = 2;
  } else {
    // (rho^2 + cr^2 + (z - cz)^2 - R^2)^2 = 4 cr^2 rho^2.
    const double cr = P.c.x() * sigma, cz = P.c.y() * sigma, R = P.rho * sigma;
    const double g0 = A0 + cr * cr + (z0 - cz) * (z0 - cz) - R * R;
    const double g1 = A1 + 2 * (z0 - cz) * z1, g2 = A2 + z1 * z1;
    co[0] = g0 * g0 - 4 * cr * cr * A0;
    co[1] = 2 * g0 * g1 - 4 * cr * cr * A1;
    co[2] = g1 * g1 + 2 * g0 * g2 - 4 * cr * cr * A2;
    co[3] = 2 * g1 * g2;
    co[4] = g2 * g2;
    deg = 4;
  }
  double mag = 0;
  for (double v : co) mag += std::abs(v);
  double roots[8];
  const double sm = s_max * sigma;
  const int n = poly_roots_in(co, deg, -sm, sm, 64 * kEps * mag * std::pow(std::max(1.0, sm), deg), roots);
  for (int i = 0; i < n; ++i) out[i] = p + (roots[i] / sigma) * d;
  return n;
}

int circle_surface_intersections(const Circle3& C, const Patch& P, Vec3* out) {
  if (C.radius == 0) {
    // A point: on the surface only to rounding; report it when it is close.
    const Vec2 q = patch_local(P, C.center);
    const double g = patch_surface_function(P, q);
    const double size = std::max({q.norm(), P.rho, P.p0.norm(), P.p1.norm()});
    if (std::abs(g) <= 1e-9 * size) out[0] = C.center;
    return std::abs(g) <= 1e-9 * size ? 1 : 0;
  }
  const CircleInAxisFrame k = circle_in_axis_frame(C, P);
  Poly G, Ga;
  if (P.straight) {
    // (off - n_z z)^2 = n_r^2 q, times (1+t^2)^2.
    const double nr = P.n.x(), nz = P.n.y(), off = P.off * k.sigma;
    const Poly E = axpy(off, k.one, -nz, k.Z);
    G = axpy(1, mul(E, E), -nr * nr, k.Q);
    const Poly Ea = axpy(std::abs(off), k.one, std::abs(nz), mul_abs(k.Z, Poly{{1}, 0}));
    Ga = axpy(1, mul(Ea, Ea), nr * nr, k.Qa);
  } else {
    // (q + cr^2 + (z - cz)^2 - R^2)^2 = 4 cr^2 q, times (1+t^2)^4.
    const double cr = P.c.x() * k.sigma, cz = P.c.y() * k.sigma, R = P.rho * k.sigma;
    const Poly Zc = axpy(1, k.Z, -cz, k.one);
    const Poly one2 = mul(k.one, k.one);
    const Poly H = axpy(1, axpy(1, k.Q, cr * cr - R * R, one2), 1, mul(Zc, Zc));
    G = axpy(1, mul(H, H), -4 * cr * cr, mul(k.Q, one2));
    const Poly Zca = axpy(1, mul_abs(k.Z, Poly{{1}, 0}), std::abs(cz), k.one);
    const Poly Ha = axpy(1, axpy(1, k.Qa, cr * cr + R * R, one2), 1, mul(Zca, Zca));
    Ga = axpy(1, mul(Ha, Ha), 4 * cr * cr, mul(k.Qa, one2));
  }
  if (max_abs(G) <= 256 * kEps * max_abs(Ga)) return 0;  // C lies on the surface: no isolated points
  double th[18];
  const int n = trig_poly_roots(G.c, G.n, th);
  for (int i = 0; i < n; ++i) out[i] = k.point(th[i], C);
  return n;
}

}  // namespace revdist
