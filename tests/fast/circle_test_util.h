// Test support for the circle kernel: seeded generators, rigid motions, and an
// independent long-double reference (dense sampling of both parameterisations,
// every sampled local minimum polished by Newton).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "compare/random_geometry.h"
#include "core/circle3.h"

namespace revdist::testing_circles {

inline std::uint64_t test_seed() {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t seed = s ? std::strtoull(s, nullptr, 10) : 20261121u;
  std::printf("REVDIST_SEED=%llu\n", static_cast<unsigned long long>(seed));
  return seed;
}

using revdist::Motion;
using revdist::Rng;
using revdist::random_motion;

inline double pair_scale(const Circle3& a, const Circle3& b) {
  return std::max({a.radius, b.radius, (a.center - b.center).norm()});
}

// ---- long-double reference ---------------------------------------------------

using LD = long double;
struct V3 {
  LD x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(LD s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline LD dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 unit(V3 a) { return (1 / std::sqrt(dot(a, a))) * a; }
inline V3 ld(const Vec3& v) { return {v[0], v[1], v[2]}; }

struct FrameL {
  V3 c, n, u, v;
  LD r;
};
inline FrameL frame_l(const Circle3& c) {
  FrameL f;
  f.c = ld(c.center);
  const LD m = std::max({std::abs(LD(c.normal[0])), std::abs(LD(c.normal[1])), std::abs(LD(c.normal[2]))});
  f.n = unit((1 / m) * ld(c.normal));
  const V3 e = std::abs(f.n.x) < 0.6L ? V3{1, 0, 0} : (std::abs(f.n.y) < 0.6L ? V3{0, 1, 0} : V3{0, 0, 1});
  f.u = unit(cross(f.n, e));
  f.v = cross(f.n, f.u);
  f.r = c.radius;
  return f;
}

// Squared distance from P(θ) on p to circle q, and its θ-derivatives.
struct RefF {
  LD f, f1, f2;
};
inline RefF ref_f(const FrameL& p, const FrameL& q, LD th) {
  const LD c = std::cos(th), s = std::sin(th);
  const V3 d = p.c - q.c;
  const V3 P = d + p.r * (c * p.u + s * p.v), P1 = p.r * (c * p.v - s * p.u), P2 = (-p.r) * (c * p.u + s * p.v);
  const LD X = dot(P, q.u), Y = dot(P, q.v), Z = dot(P, q.n);
  const LD X1 = dot(P1, q.u), Y1 = dot(P1, q.v), Z1 = dot(P1, q.n);
  const LD X2 = dot(P2, q.u), Y2 = dot(P2, q.v), Z2 = dot(P2, q.n);
  const LD rho = std::sqrt(X * X + Y * Y), e = rho - q.r;
  RefF r{Z * Z + e * e, 0, -1};
  if (rho == 0) return r;
  const LD r1 = (X * X1 + Y * Y1) / rho, r2 = (X1 * X1 + Y1 * Y1 + X * X2 + Y * Y2 - r1 * r1) / rho;
  r.f1 = 2 * (Z * Z1 + e * r1);
  r.f2 = 2 * (Z1 * Z1 + Z * Z2 + r1 * r1 + e * r2);
  return r;
}

// min over θ of f for p against q: n samples, each sampled local minimum polished
// by a bracketed Newton iteration.
inline LD ref_min_one(const FrameL& p, const FrameL& q, int n) {
  const LD two_pi = 2 * 3.141592653589793238462643383279502884L;
  std::vector<LD> f(n);
  for (int i = 0; i < n; ++i) f[i] = ref_f(p, q, two_pi * i / n).f;
  LD best = *std::min_element(f.begin(), f.end());
  for (int i = 0; i < n; ++i) {
    const LD fl = f[(i + n - 1) % n], fr = f[(i + 1) % n];
    if (!(f[i] <= fl && f[i] <= fr)) continue;
    LD lo = two_pi * (i - 1) / n, hi = two_pi * (i + 1) / n, th = two_pi * i / n;
    for (int it = 0; it < 100; ++it) {
      const RefF r = ref_f(p, q, th);
      best = std::min(best, r.f);
      if (r.f1 > 0) hi = th; else lo = th;
      LD tn = r.f2 > 0 ? th - r.f1 / r.f2 : 0.5L * (lo + hi);
      if (!(tn > lo && tn < hi)) tn = 0.5L * (lo + hi);
      if (std::abs(tn - th) < 1e-19L) break;
      th = tn;
    }
    best = std::min(best, ref_f(p, q, th).f);
  }
  return best;
}

// The reference distance: both parameterisations, the smaller minimum.
inline double ref_distance(const Circle3& a, const Circle3& b, int n = 4096) {
  const FrameL fa = frame_l(a), fb = frame_l(b);
  LD m = ref_min_one(fb, fa, n);
  if (a.radius > 0) m = std::min(m, ref_min_one(fa, fb, n));
  return static_cast<double>(std::sqrt(std::max(LD(0), m)));
}

// Distance from x to circle c in long double (witness checks).
inline double ref_point_circle(const Vec3& x, const Circle3& c) {
  const FrameL f = frame_l(c);
  const V3 d = ld(x) - f.c;
  const LD X = dot(d, f.u), Y = dot(d, f.v), Z = dot(d, f.n);
  const LD e = std::sqrt(X * X + Y * Y) - f.r;
  return static_cast<double>(std::sqrt(Z * Z + e * e));
}

}  // namespace revdist::testing_circles
