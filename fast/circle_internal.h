// Internals shared by the circle-circle distance and binormal routines (paper
// section 3.2, Appendix A): the power-of-two normalisation, the circle-in-frame
// coefficients, and a real-root finder for the small polynomials in t = tan(θ/2).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/circle3.h"

namespace revdist::circle_detail {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;

// Unit vector along n. n may be tiny or huge: dividing by its largest component
// first keeps |n|^2 away from underflow and overflow.
inline Vec3 unit_normal(const Vec3& n) {
  const double m = n.cwiseAbs().maxCoeff();
  const Vec3 s = n / m;
  return s / s.norm();
}

// An orthonormal pair (u, v) with u x v = n (n unit).
inline void plane_basis(const Vec3& n, Vec3* u, Vec3* v) {
  // Cross with the coordinate axis least aligned with n: |n x e| >= sqrt(2/3).
  int k = 0;
  if (std::abs(n[1]) < std::abs(n[k])) k = 1;
  if (std::abs(n[2]) < std::abs(n[k])) k = 2;
  *u = n.cross(Vec3::Unit(k)).normalized();
  *v = n.cross(*u);
}

// The power of two that brings s into [1/2, 1) when multiplied (1 for s <= 0
// or not finite): lengths multiplied by it are exact.
inline double pow2_inverse(double s) {
  if (!(s > 0) || !std::isfinite(s)) return 1.0;
  int e;
  std::frexp(s, &e);
  return std::ldexp(1.0, -e);
}

// The power of two for max(radii, |C_a - C_b|): the kernel is then bit-for-bit
// invariant under scaling by powers of two and its tolerances are plain
// multiples of ε.
inline double circle_pair_sigma(const Circle3& a, const Circle3& b) {
  return pow2_inverse(std::max({a.radius, b.radius, (a.center - b.center).cwiseAbs().maxCoeff()}));
}

// A circle prepared for the kernel: unit normal and in-plane basis.
struct CircleFrame {
  Vec3 center;
  Vec3 n, u, v;  // unit, u x v = n
  double radius;
};

inline CircleFrame make_frame(const Circle3& c) {
  CircleFrame f;
  f.center = c.center;
  f.n = unit_normal(c.normal);
  plane_basis(f.n, &f.u, &f.v);
  f.radius = c.radius;
  return f;
}

// Circle p (parameter θ) written in the frame (u_q, v_q, n_q) of circle q with
// origin C_q, every length multiplied by sigma (a power of two, so exactly):
//   Δ(θ) = P(θ) - C_q = (X, Y, Z),  X = x0 + x1 cosθ + x2 sinθ  (same for Y, Z),
//   |Δ|^2 = a0 + a1 cosθ + b1 sinθ  (degree 1 exactly: P runs on a circle),
//   f(θ) = Z^2 + (ρ - R)^2 with ρ = hypot(X, Y), the squared distance from P to q.
struct PairCoeffs {
  double x0, x1, x2, y0, y1, y2, z0, z1, z2;
  double a0, a1, b1;
  double R;  // radius of q (scaled)
};

inline PairCoeffs make_coeffs(const CircleFrame& p, const CircleFrame& q, double sigma) {
  PairCoeffs k;
  const Vec3 D = (p.center - q.center) * sigma;
  const double Rp = p.radius * sigma;
  const Vec3 U = p.u * Rp, V = p.v * Rp;
  k.x0 = D.dot(q.u);
  k.x1 = U.dot(q.u);
  k.x2 = V.dot(q.u);
  k.y0 = D.dot(q.v);
  k.y1 = U.dot(q.v);
  k.y2 = V.dot(q.v);
  k.z0 = D.dot(q.n);
  k.z1 = U.dot(q.n);
  k.z2 = V.dot(q.n);
  k.a0 = D.squaredNorm() + Rp * Rp;
  k.a1 = 2 * D.dot(U);
  k.b1 = 2 * D.dot(V);
  k.R = q.radius * sigma;
  return k;
}

// The same coefficients for the parameter shifted by phi: θ = phi + θ'.
inline PairCoeffs rotate_coeffs(const PairCoeffs& k, double c, double s) {
  PairCoeffs r = k;
  r.x1 = k.x1 * c + k.x2 * s;
  r.x2 = k.x2 * c - k.x1 * s;
  r.y1 = k.y1 * c + k.y2 * s;
  r.y2 = k.y2 * c - k.y1 * s;
  r.z1 = k.z1 * c + k.z2 * s;
  r.z2 = k.z2 * c - k.z1 * s;
  r.a1 = k.a1 * c + k.b1 * s;
  r.b1 = k.b1 * c - k.a1 * s;
  return r;
}

// Squared distance from P(θ) to circle q. ρ - R and Z are formed directly (not
// |Δ|^2 + R^2 - 2Rρ), so the value keeps its relative accuracy when the circles
// nearly meet.
inline double sq_dist(const PairCoeffs& k, double c, double s) {
  const double X = k.x0 + k.x1 * c + k.x2 * s;
  const double Y = k.y0 + k.y1 * c + k.y2 * s;
  const double Z = k.z0 + k.z1 * c + k.z2 * s;
  const double e = std::sqrt(X * X + Y * Y) - k.R;
  return Z * Z + e * e;
}

struct Deriv {
  double f, f1, f2, rho;
};

// f and its first two θ-derivatives. At ρ = 0 (P on q's axis: a cusp, a local
// maximum of f when the circle crosses the axis) f1 is one-sided garbage and
// f2 is reported negative so callers take a guarded descent step.
inline Deriv sq_dist_derivs(const PairCoeffs& k, double c, double s) {
  const double X = k.x0 + k.x1 * c + k.x2 * s, X1 = k.x2 * c - k.x1 * s, X2 = -(k.x1 * c + k.x2 * s);
  const double Y = k.y0 + k.y1 * c + k.y2 * s, Y1 = k.y2 * c - k.y1 * s, Y2 = -(k.y1 * c + k.y2 * s);
  const double Z = k.z0 + k.z1 * c + k.z2 * s, Z1 = k.z2 * c - k.z1 * s, Z2 = -(k.z1 * c + k.z2 * s);
  const double rho = std::sqrt(X * X + Y * Y);
  const double e = rho - k.R;
  Deriv d;
  d.f = Z * Z + e * e;
  d.rho = rho;
  if (rho == 0) {
    d.f1 = 2 * Z * Z1;
    d.f2 = -1;
    return d;
  }
  const double r1 = (X * X1 + Y * Y1) / rho;
  const double r2 = (X1 * X1 + Y1 * Y1 + X * X2 + Y * Y2 - r1 * r1) / rho;
  d.f1 = 2 * (Z * Z1 + e * r1);
  d.f2 = 2 * (Z1 * Z1 + Z * Z2 + r1 * r1 + e * r2);
  return d;
}

// Coefficients, in t = tan(θ/2), of q(θ)(1 + t^2) for q = q0 + q1 cosθ + q2 sinθ.
inline void trig1_to_t(double q0, double q1, double q2, double out[3]) {
  out[0] = q0 + q1;
  out[1] = 2 * q2;
  out[2] = q0 - q1;
}

// out = a * b (degrees na, nb).
inline void poly_mul(const double* a, int na, const double* b, int nb, double* out) {
  for (int i = 0; i <= na + nb; ++i) out[i] = 0;
  for (int i = 0; i <= na; ++i)
    for (int j = 0; j <= nb; ++j) out[i + j] += a[i] * b[j];
}

inline double poly_eval(const double* a, int n, double t) {
  double r = a[n];
  for (int i = n - 1; i >= 0; --i) r = r * t + a[i];
  return r;
}

// Real roots in [lo, hi] of the polynomial a[0] + a[1] t + ... + a[n] t^n
// (n <= 8), sorted. Roots of even multiplicity, where p touches 0 without a sign
// change, are reported when |p| at a local extremum is within rounding of 0
// (tol_abs). Returns the count.
int poly_roots_in(const double* a, int n, double lo, double hi, double tol_abs, double* roots);

// Real roots, as angles in (-π, π], of a trig polynomial given by its t-form
// a[0..n] (t = tan(θ/2), n <= 8, the polynomial times (1+t^2)^(n/2)) over the
// whole circle: the chart t in [-1, 1] for |θ| <= π/2 and the chart turned by π
// (t' = -1/t) for the rest, so no root is lost at infinity. Touching roots are
// kept when |p| at a local extremum is within 64nε·Σ|a_i|. The charts overlap,
// so roots near the seam may appear twice. th must hold 2n entries.
// coeff_err bounds Σ_i |a_i - exact a_i| when the coefficients came out of a
// cancelling sum (their size then says nothing about their error): a touching
// root of the exact polynomial may sit that far from 0, so the tolerance grows
// by its worst effect on |t| <= 1.25.
int trig_poly_roots(const double* a, int n, double* th, double coeff_err = 0);
// The same restricted to the angle window [th0, th1] (th1 - th0 <= 2π; it may
// cross the seam at ±π): every root in the window, possibly a few just outside
// (the charts overlap; up to 4(n + 1) entries with duplicates). The same
// charts and tolerance as above. Returns -1 (nothing lost: the caller falls
// back to the whole circle) when more than cap entries would be written.
int trig_poly_roots_window(const double* a, int n, double th0, double th1, double* th, int cap,
                           double coeff_err = 0);

// Angles where ρ^2 = X^2 + Y^2 of circle p in q's frame is critical:
// roots of (ρ^2)'/2 = X X' + Y Y', a quartic in t (at most 8 angles: two charts).
inline int rho2_critical_angles(const PairCoeffs& k, double* th) {
  double X[3], Y[3], Xd[3], Yd[3], q[5], q2[5];
  trig1_to_t(k.x0, k.x1, k.x2, X);
  trig1_to_t(k.y0, k.y1, k.y2, Y);
  trig1_to_t(0, k.x2, -k.x1, Xd);  // X' = x2 cosθ - x1 sinθ
  trig1_to_t(0, k.y2, -k.y1, Yd);
  poly_mul(X, 2, Xd, 2, q);
  poly_mul(Y, 2, Yd, 2, q2);
  for (int i = 0; i <= 4; ++i) q[i] += q2[i];
  return trig_poly_roots(q, 4, th);
}

inline double wrap_pi(double x) {
  while (x > kPi) x -= 2 * kPi;
  while (x <= -kPi) x += 2 * kPi;
  return x;
}

}  // namespace revdist::circle_detail
