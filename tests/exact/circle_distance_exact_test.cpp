// Tests of exact/circle_distance_exact: closed forms with tolerance 0 (the
// expected value lies in [lower, upper]), every named degenerate case, swap
// symmetry, and random pairs against an independent long-double brute force.
#include "exact/circle_distance_exact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace revdist {
namespace {

Circle3 C(Vec3 c, Vec3 n, double r) { return Circle3{c, n, r}; }

double scale_of(const Circle3& a, const Circle3& b) {
  return std::max({a.radius, b.radius, (a.center - b.center).norm()});
}

// Width target of the brief: 1e-25 relative to the scale (default options ask 1e-30).
constexpr double kRelWidth = 1e-25;

const char* status_name(ExactStatus s) {
  switch (s) {
    case ExactStatus::ok: return "ok";
    case ExactStatus::infinitely_many: return "infinitely_many";
    case ExactStatus::not_certified: return "not_certified";
  }
  return "?";
}

// `expected` must be the correctly rounded double of the true value (exact
// inputs, one IEEE operation): then it lies in the outward-rounded [lower, upper].
void expect_certified(const Circle3& a, const Circle3& b, double expected, ExactStatus status,
                      const char* what) {
  SCOPED_TRACE(what);
  for (int swap = 0; swap < 2; ++swap) {
    SCOPED_TRACE(swap ? "swapped" : "as given");
    const ExactCircleResult r =
        swap ? circle3_circle3_distance_exact(b, a) : circle3_circle3_distance_exact(a, b);
    EXPECT_EQ(status_name(r.status), std::string(status_name(status))) << r.reason;
    EXPECT_LE(r.lower, expected);
    EXPECT_GE(r.upper, expected);
    EXPECT_LE(r.width, kRelWidth * scale_of(a, b));
    EXPECT_FALSE(r.contact);
    EXPECT_GT(r.lower, 0.0);
    // The decimal is a point of the interval, printed with >= 30 digits.
    const long double dec = std::strtold(r.decimal.c_str(), nullptr);
    EXPECT_NEAR(static_cast<double>(dec), expected, 4e-16 * expected) << r.decimal;
    EXPECT_GE(r.decimal.size(), 30u);
    // Witnesses: |p_a − p_b| is the distance, up to double rounding of the
    // points (a few ulps of the largest coordinate).
    const double coord = std::max(r.point_a.cwiseAbs().maxCoeff(), r.point_b.cwiseAbs().maxCoeff());
    EXPECT_NEAR((r.point_a - r.point_b).norm(), expected, 1e-12 * scale_of(a, b) + 8e-16 * coord);
  }
}

void expect_contact(const Circle3& a, const Circle3& b, const char* what) {
  SCOPED_TRACE(what);
  for (int swap = 0; swap < 2; ++swap) {
    const ExactCircleResult r =
        swap ? circle3_circle3_distance_exact(b, a) : circle3_circle3_distance_exact(a, b);
    EXPECT_TRUE(r.contact) << r.reason;
    EXPECT_EQ(r.lower, 0.0);
    EXPECT_EQ(r.upper, 0.0);
    EXPECT_EQ(r.distance, 0.0);
    EXPECT_EQ(r.decimal, "0");
    EXPECT_NE(r.status, ExactStatus::not_certified) << r.reason;
    EXPECT_NEAR((r.point_a - r.point_b).norm(), 0.0, 1e-12 * scale_of(a, b));
  }
}

// ---------------------------------------------------------------- brute force

struct LdVec {
  long double x, y, z;
};

// Independent reference: dense sampling of b plus golden-section polishing,
// each sample's distance to a in closed form. An upper bound on the true
// distance up to long-double rounding; close to it after polishing.
long double brute_force(const Circle3& a, const Circle3& b) {
  auto ld = [](const Vec3& v) { return LdVec{v.x(), v.y(), v.z()}; };
  const LdVec ca = ld(a.center), cb = ld(b.center);
  LdVec n = ld(a.normal);
  const long double nl = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  n = {n.x / nl, n.y / nl, n.z / nl};
  LdVec m = ld(b.normal);
  const long double ml = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
  if (ml > 0) m = {m.x / ml, m.y / ml, m.z / ml};
  LdVec e = std::fabs(m.x) < 0.6L ? LdVec{1, 0, 0} : LdVec{0, 1, 0};
  LdVec u{e.y * m.z - e.z * m.y, e.z * m.x - e.x * m.z, e.x * m.y - e.y * m.x};
  const long double ul = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
  u = {u.x / ul, u.y / ul, u.z / ul};
  const LdVec v{m.y * u.z - m.z * u.y, m.z * u.x - m.x * u.z, m.x * u.y - m.y * u.x};
  const long double R = a.radius, r = b.radius;
  auto dist = [&](long double t) {
    const long double c = std::cos(t), s = std::sin(t);
    const LdVec d{cb.x + r * (c * u.x + s * v.x) - ca.x, cb.y + r * (c * u.y + s * v.y) - ca.y,
                  cb.z + r * (c * u.z + s * v.z) - ca.z};
    const long double h = d.x * n.x + d.y * n.y + d.z * n.z;
    const LdVec p{d.x - h * n.x, d.y - h * n.y, d.z - h * n.z};
    const long double rho = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    return std::hypot(h, rho - R);
  };
  const int N = 4096;
  const long double step = 2 * M_PIl / N;
  std::vector<long double> samples(N);
  for (int i = 0; i < N; ++i) samples[i] = dist(i * step);
  // Polish the 8 smallest sampled local minima (plateaus count once).
  std::vector<std::pair<long double, int>> minima;
  for (int i = 0; i < N; ++i) {
    const long double d0 = samples[i];
    if (d0 <= samples[(i + N - 1) % N] && d0 < samples[(i + 1) % N]) minima.push_back({d0, i});
  }
  if (minima.empty()) minima.push_back({samples[0], 0});
  std::sort(minima.begin(), minima.end());
  if (minima.size() > 8) minima.resize(8);
  long double best = INFINITY;
  for (const auto& [d0, i] : minima) {
    long double lo = (i - 1) * step, hi = (i + 1) * step;  // golden section on the bracket
    const long double g = (std::sqrt(5.0L) - 1) / 2;
    long double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    long double f1 = dist(x1), f2 = dist(x2);
    for (int it = 0; it < 120; ++it) {
      if (f1 < f2) {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = dist(x1);
      } else {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = dist(x2);
      }
    }
    best = std::min({best, d0, f1, f2});
  }
  return best;
}

// Certified interval against the brute force: lower below it, upper at it
// (to `tol`, the brute force's own accuracy), width within the target.
ExactCircleResult expect_matches_brute_force(const Circle3& a, const Circle3& b, double tol = 1e-12) {
  const auto r = circle3_circle3_distance_exact(a, b);
  EXPECT_NE(r.status, ExactStatus::not_certified) << r.reason;
  // Sampling either circle; fmin skips the NaN of a zero-normal point.
  const double bf = static_cast<double>(std::fmin(brute_force(a, b), brute_force(b, a)));
  if (r.contact) {
    EXPECT_LT(bf, 1e-6);
    return r;
  }
  EXPECT_LE(r.lower, bf * (1 + 1e-15));
  EXPECT_NEAR(r.upper, bf, tol * scale_of(a, b));
  EXPECT_LE(r.width, kRelWidth * scale_of(a, b));
  return r;
}

unsigned seed_from_env() {
  const char* s = std::getenv("REVDIST_SEED");
  return s ? static_cast<unsigned>(std::strtoul(s, nullptr, 10)) : 20240611u;
}

// ---------------------------------------------------------------- closed forms

// A distance far below the pair's scale: circles of radius R = 1e50 (and
// 1e100) about perpendicular axes (z and y), centres 1 apart along x. They
// share no point, and the closest pairs are (R, 0, 0) and (1 + R, 0, 0) (and
// their mirrors), exactly 1 apart: nearby pairs are farther by about R times
// the squared angles. `distance` must be the nearest double, 1, with status
// ok: at the scale's relative width alone the third hostile review got
// [0, 9.9e13], "ok", distance 4.9e13.
TEST(CircleDistanceExact, DistanceFarBelowTheScaleIsTheNearestDouble) {
  for (double R : {1e50, 1e100}) {
    const auto r = circle3_circle3_distance_exact(C({0, 0, 0}, {0, 0, 1}, R), C({1, 0, 0}, {0, 1, 0}, R));
    ASSERT_EQ(r.status, ExactStatus::ok) << R << " " << r.reason;
    EXPECT_EQ(r.distance, 1.0) << R;
    EXPECT_LE(r.lower, 1.0) << R;
    EXPECT_GE(r.upper, 1.0) << R;
  }
}

TEST(CircleDistanceExact, CoplanarDisjoint) {
  // |C| − R_a − R_b with |C| = 5, normals not unit.
  expect_certified(C({0, 0, 0}, {0, 0, 3}, 1), C({3, 4, 0}, {0, 0, -0.5}, 2), 2.0,
                   ExactStatus::ok, "coplanar disjoint");
  // Tilted plane: normal (1,2,2), centre offset (2,-2,1)*3 ⟂ normal, |offset| = 9.
  expect_certified(C({1, 1, 1}, {1, 2, 2}, 2.5), C({7, -5, 4}, {2, 4, 4}, 1.5), 5.0,
                   ExactStatus::ok, "coplanar disjoint, tilted plane");
  const auto r = circle3_circle3_distance_exact(C({0, 0, 0}, {0, 0, 3}, 1), C({3, 4, 0}, {0, 0, 1}, 2));
  EXPECT_EQ(r.binormals, 4);  // the two points of b on the centre line, each with a near and a far line
}

TEST(CircleDistanceExact, ConcentricCoplanar) {
  expect_certified(C({1, 2, 3}, {0, 0, 1}, 1), C({1, 2, 3}, {0, 0, -7}, 3), 2.0,
                   ExactStatus::infinitely_many, "concentric coplanar");
}

TEST(CircleDistanceExact, CoaxialStacked) {
  // √(ΔR² + h²) = √(9 + 16).
  expect_certified(C({0, 0, 0}, {0, 0, 2}, 1), C({0, 0, 4}, {0, 0, -1}, 4), 5.0,
                   ExactStatus::infinitely_many, "coaxial stacked");
  // Oblique axis n = (1,2,2), h = |2n| = 6, ΔR = 8: 10.
  expect_certified(C({0, 0, 0}, {1, 2, 2}, 9), C({2, 4, 4}, {-0.5, -1, -1}, 1), 10.0,
                   ExactStatus::infinitely_many, "coaxial oblique");
  const auto r = circle3_circle3_distance_exact(C({0, 0, 0}, {0, 0, 2}, 1), C({0, 0, 4}, {0, 0, -1}, 4));
  EXPECT_EQ(r.binormals, -1);
}

TEST(CircleDistanceExact, ConcentricTilted) {
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 3), C({0, 0, 0}, {1, 0, 1}, 1), 2.0, ExactStatus::ok,
                   "concentric tilted");
  expect_certified(C({5, -1, 2}, {1, 2, 3}, 0.75), C({5, -1, 2}, {-3, 1, 0.5}, 2), 1.25,
                   ExactStatus::ok, "concentric tilted, generic normals");
}

TEST(CircleDistanceExact, PointCircle) {
  // ρ = 4, h = 3, R = 1: √(9 + 9).
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({4, 0, 3}, {0, 0, 0}, 0), std::sqrt(18.0),
                   ExactStatus::ok, "point–circle");
  // On the axis: √(h² + R²) = 2.5, every point of a is closest.
  expect_certified(C({0, 0, 0}, {0, 0, 5}, 1.5), C({0, 0, 2}, {1, 0, 0}, 0), 2.5,
                   ExactStatus::infinitely_many, "point on the axis");
  expect_certified(C({1, 2, 3}, {0, 0, 0}, 0), C({4, 6, 3}, {0, 0, 1}, 0), 5.0, ExactStatus::ok,
                   "point–point");
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 5), C({3, 4, 0}, {0, 0, 0}, 0), "point on the circle");
  expect_contact(C({1, 2, 3}, {0, 0, 0}, 0), C({1, 2, 3}, {0, 1, 0}, 0), "same point");
}

TEST(CircleDistanceExact, Contact) {
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 1}, {0, 1, 0}, 1), "intersecting, transversal");
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 1}, {1, 0, 0}, 1), "touching, tangent in 3D");
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 2), C({1, 0, 0}, {0, 0, 2}, 1), "coplanar, internally tangent");
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 1, 0}, {0, 0, 1}, 1), "coplanar, two shared points");
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 5), C({3, 4, 2}, {4, -3, 0}, 2),
                 "meridian circle through a point of a");
  // Meridian circle centred on a with radius 2R: touches a at (−1, 0, 0).
  expect_contact(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 0}, {0, 1, 0}, 2), "meridian, r_b = 2R");
  // Same circle given twice (coaxial path).
  expect_contact(C({1, 2, 3}, {1, 1, 0}, 2), C({1, 2, 3}, {-2, -2, 0}, 2), "identical circles");
  // Shared point with irrational coordinates: b through (1/√2, 1/√2, 0)? Not
  // representable; instead b's plane x = y meets a at (±1/√2, ±1/√2, 0) and b is
  // centred on the z axis with radius² = 1 + 1 = 2 ⇒ radius √2 is not a double.
  // A double radius sqrt(2.0) misses by ~1e-17: exactly NOT contact.
  const auto r = circle3_circle3_distance_exact(C({0, 0, 0}, {0, 0, 1}, 1),
                                                C({0, 0, 1}, {1, -1, 0}, std::sqrt(2.0)));
  EXPECT_FALSE(r.contact);
  EXPECT_GT(r.lower, 0.0);
  EXPECT_LT(r.upper, 1e-15);
  EXPECT_NE(r.status, ExactStatus::not_certified) << r.reason;
}

TEST(CircleDistanceExact, LinkedCircles) {
  // Hopf link where b (meridian, centred on a, radius R) stays at distance R
  // from a everywhere: f constant, H ≡ 0.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 0}, {0, 1, 0}, 1), 1.0,
                   ExactStatus::infinitely_many, "Hopf link, meridian radius R");
  // A generic linked pair, against brute force.
  const auto r = expect_matches_brute_force(C({0, 0, 0}, {0, 0, 1}, 1),
                                            C({0.5, 0.25, 0.125}, {0.25, 1, 0.5}, 0.875));
  EXPECT_EQ(r.status, ExactStatus::ok) << r.reason;
}

TEST(CircleDistanceExact, Villarceau) {
  // Torus R = 5, r = 3: its Villarceau circles (radius 5, centre (0, ±3, 0),
  // plane 3x = ±4z) lie on the torus, so every point is at distance r = 3 from
  // the core circle: constant distance 3, H ≡ 0.
  const Circle3 core = C({0, 0, 0}, {0, 0, 1}, 5);
  expect_certified(core, C({0, 3, 0}, {3, 0, -4}, 5), 3.0, ExactStatus::infinitely_many,
                   "Villarceau circle vs core");
  expect_certified(core, C({0, -3, 0}, {3, 0, 4}, 5), 3.0, ExactStatus::infinitely_many,
                   "mirror Villarceau circle vs core");
  EXPECT_EQ(circle3_circle3_distance_exact(core, C({0, 3, 0}, {3, 0, -4}, 5)).binormals, -1);
}

TEST(CircleDistanceExact, MeridianLargeRadius) {
  // b in a meridian plane, centred on a, radius r_b > 2R: f is NOT constant
  // (H ≡ 0 but f' ∝ L on the outer arc); min r_b − 2R at the far side.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 0}, {0, 1, 0}, 3), 1.0, ExactStatus::ok,
                   "meridian r_b = 3R");
  expect_certified(C({0, 0, 0}, {0, 0, 2}, 1.5), C({0, 1.5, 0}, {7, 0, 0}, 5), 2.0, ExactStatus::ok,
                   "meridian r_b = 5, R = 1.5");
  // r_b < 2R: the meridian circle stays at distance r_b (constant arc wins).
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 0}, {0, 1, 0}, 0.5), 0.5,
                   ExactStatus::infinitely_many, "meridian r_b = R/2");
}

TEST(CircleDistanceExact, ThroughTheAxis) {
  // b in the xz-plane, tangent to the axis of a at the centre of a:
  // f(t) = 2 r_b (1 + cos t)(r_b − R) + R². For r_b > R the minimum R is at
  // the axis point, where every point of a is closest: a continuum.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({2, 0, 0}, {0, 1, 0}, 2), 1.0,
                   ExactStatus::infinitely_many, "closest point of b on the axis of a");
  // For r_b < R the minimum |R − 2 r_b| is at (2 r_b, 0, 0): one pair.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({0.25, 0, 0}, {0, 1, 0}, 0.25), 0.5,
                   ExactStatus::ok, "b through the axis, minimum away from it");
  // b crossing the axis transversally (a double root of H there, a local max of f).
  // b crosses the axis at z = ±√2.
  expect_matches_brute_force(C({0, 0, 0}, {0, 0, 1}, 1), C({1, -1, 0}, {1, 1, 0}, 2));
}

TEST(CircleDistanceExact, TangentNotTouching) {
  // Coplanar, externally at distance 0.25 along x (tangent lines parallel).
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({2.25, 0, 0}, {0, 0, 1}, 1), 0.25, ExactStatus::ok,
                   "coplanar, nearly tangent");
  // Parallel planes, not coaxial: 2D gap 1 and height 1: √2.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1), C({3, 0, 1}, {0, 0, 1}, 1), std::sqrt(2.0),
                   ExactStatus::ok, "parallel planes");
}

TEST(CircleDistanceExact, MirrorSymmetric) {
  // Symmetric under y → −y: the roots of the binormal polynomial are double.
  const Circle3 a = C({0, 0, 0}, {0, 0, 1}, 1);
  for (const Circle3& b : {C({0, 0, 1}, {1, 0, 0}, 2), C({3, 0, 0.5}, {1, 0, 1}, 1),
                           C({0.5, 0, 2}, {0, 0, 1}, 0.25), C({2, 0, 0}, {0, 1, 0}, 0.5)})
    expect_matches_brute_force(a, b);
  // b centred on the axis of a at height 1, radius 2, in the plane x = 0:
  // d²(t) = 6 + 4 sin t − 4|cos t|, minimal at the mirror pair t = −π/4, −3π/4:
  // d = 2 − √2 (not a double: compare the decimal to 30 digits).
  const auto r = circle3_circle3_distance_exact(a, C({0, 0, 1}, {1, 0, 0}, 2));
  EXPECT_EQ(r.status, ExactStatus::ok) << r.reason;
  EXPECT_EQ(r.decimal.substr(0, 32), "5.857864376269049511983112757903");
  EXPECT_EQ(r.binormals % 2, 0);
}

TEST(CircleDistanceExact, Scales) {
  const Circle3 a = C({0, 0, 0}, {0, 0, 3}, 1), b = C({3, 4, 0}, {0, 0, -0.5}, 2);
  for (double s : {0x1p-20, 0x1p20, 0x1p-40}) {
    expect_certified(C(a.center * s, a.normal, a.radius * s), C(b.center * s, b.normal, b.radius * s),
                     2.0 * s, ExactStatus::ok, "power-of-two scale");
  }
  // Decimal scales 1e-6 and 1e6 (inputs no longer exact multiples): brute force.
  const Circle3 b2 = C({0.5, 0.25, 0.125}, {0.25, 1, 0.5}, 0.875);
  for (double s : {1e-6, 1e6}) {
    const Circle3 as = C(a.center * s, a.normal, a.radius * s), bs = C(b2.center * s, b2.normal, b2.radius * s);
    EXPECT_EQ(expect_matches_brute_force(as, bs).status, ExactStatus::ok);
  }
}

TEST(CircleDistanceExact, FarFromOrigin) {
  const Vec3 t(1e6, -1e6, 1e6);
  expect_certified(C(t + Vec3(0, 0, 0), {0, 0, 3}, 1), C(t + Vec3(3, 4, 0), {0, 0, -0.5}, 2), 2.0,
                   ExactStatus::ok, "coplanar disjoint, centres 1e6 away");
  expect_certified(C(t, {0, 0, 1}, 1), C(t + Vec3(1, 0, 0), {0, 1, 0}, 3), 1.0, ExactStatus::ok,
                   "meridian, centres 1e6 away");
}

TEST(CircleDistanceExact, RadiusRatio) {
  // R = 1e6, b of radius 1 in a parallel plane: ρ_min = R + 2, h = 4: √20.
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1e6), C({1e6 + 3, 0, 4}, {0, 0, 1}, 1), std::sqrt(20.0),
                   ExactStatus::ok, "radius ratio 1e6");
  expect_certified(C({0, 0, 0}, {0, 0, 1}, 1e6), C({1e6 + 3, 0, 0}, {0, 0, 1}, 1), 2.0,
                   ExactStatus::ok, "radius ratio 1e6, coplanar");
  expect_certified(C({1e6 + 3, 0, 0}, {0, 0, 1}, 1), C({0, 0, 0}, {0, 0, 1}, 1e6), 2.0,
                   ExactStatus::ok, "radius ratio 1e-6, coplanar");
}

TEST(CircleDistanceExact, InvalidInputNeverThrows) {
  const Circle3 a = C({0, 0, 0}, {0, 0, 1}, 1);
  EXPECT_EQ(circle3_circle3_distance_exact(a, C({1, 0, 0}, {0, 0, 0}, 1)).status,
            ExactStatus::not_certified);
  EXPECT_EQ(circle3_circle3_distance_exact(a, C({NAN, 0, 0}, {0, 0, 1}, 1)).status,
            ExactStatus::not_certified);
  EXPECT_EQ(circle3_circle3_distance_exact(a, C({1, 0, 0}, {0, 0, 1}, -1)).status,
            ExactStatus::not_certified);
}

// ---------------------------------------------------------------- random pairs

Circle3 random_circle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-2, 2), rad(0.1, 2);
  return C({u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, rad(rng));
}

TEST(CircleDistanceExact, RandomAgainstBruteForceAndSwap) {
  const unsigned seed = seed_from_env();
  std::printf("REVDIST_SEED=%u\n", seed);
  std::mt19937_64 rng(seed);
  double total_ms = 0;
  int calls = 0;
  for (int i = 0; i < 200; ++i) {
    SCOPED_TRACE(i);
    const Circle3 a = random_circle(rng), b = random_circle(rng);
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = circle3_circle3_distance_exact(a, b);
    total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++calls;
    const auto s = circle3_circle3_distance_exact(b, a);
    ASSERT_NE(r.status, ExactStatus::not_certified) << r.reason;
    ASSERT_NE(s.status, ExactStatus::not_certified) << s.reason;
    const long double bf = std::min(brute_force(a, b), brute_force(b, a));
    if (r.contact) {
      EXPECT_LT(bf, 1e-9);
      continue;
    }
    EXPECT_LE(r.lower, static_cast<double>(bf) * (1 + 1e-15));
    EXPECT_NEAR(r.upper, static_cast<double>(bf), 1e-12 * scale_of(a, b));
    EXPECT_LE(r.width, kRelWidth * scale_of(a, b));
    EXPECT_LE(r.lower, s.upper);  // swapped intervals overlap
    EXPECT_LE(s.lower, r.upper);
    EXPECT_GE(r.binormals, 1);
    EXPECT_LE(r.binormals, 8);
  }
  std::printf("mean time per certified distance: %.3f ms over %d calls\n", total_ms / calls, calls);
}

// Small-integer pairs hit the exact degenerate paths often: contact, axis
// crossings, H ≡ 0, parallel and perpendicular planes, shared centres.
TEST(CircleDistanceExact, IntegerPairsAgainstBruteForce) {
  const unsigned seed = seed_from_env();
  std::printf("REVDIST_SEED=%u\n", seed);
  std::mt19937_64 rng(seed + 1);
  std::uniform_int_distribution<int> c(-2, 2), nn(-1, 1), rr(0, 3);
  int contacts = 0, many = 0;
  for (int i = 0; i < 400; ++i) {
    SCOPED_TRACE(i);
    auto circle = [&] {
      Vec3 n;
      do n = Vec3(nn(rng), nn(rng), nn(rng)); while (n.isZero(0));
      return C({double(c(rng)), double(c(rng)), double(c(rng))}, n, rr(rng) == 0 ? 0.0 : double(rr(rng)));
    };
    const Circle3 a = circle(), b = circle();
    const auto r = expect_matches_brute_force(a, b, 1e-9);
    const auto s = circle3_circle3_distance_exact(b, a);
    ASSERT_NE(s.status, ExactStatus::not_certified) << s.reason;
    EXPECT_EQ(r.contact, s.contact);
    EXPECT_EQ(r.status, s.status);
    EXPECT_LE(r.lower, s.upper);
    EXPECT_LE(s.lower, r.upper);
    contacts += r.contact;
    many += r.status == ExactStatus::infinitely_many;
  }
  std::printf("contacts %d, infinitely_many %d of 400\n", contacts, many);
}

// Near-degenerate: tilt ε away from coaxial, Villarceau and meridian pairs.
TEST(CircleDistanceExact, NearDegenerate) {
  const Circle3 core = C({0, 0, 0}, {0, 0, 1}, 5);
  for (double eps : {1e-3, 1e-8, 1e-13}) {
    SCOPED_TRACE(eps);
    const Circle3 pairs[][2] = {
        {C({0, 0, 0}, {0, 0, 2}, 1), C({eps, 0, 4}, {0, 0, -1}, 4)},
        {C({0, 0, 0}, {0, 0, 2}, 1), C({0, 0, 4}, {eps, 0, -1}, 4)},
        {core, C({0, 3, 0}, {3, eps, -4}, 5)},
        {core, C({0, 3 + eps, 0}, {3, 0, -4}, 5)},
        {C({0, 0, 0}, {0, 0, 1}, 1), C({1, 0, 0}, {eps, 1, 0}, 3)},
        {C({0, 0, 0}, {0, 0, 1}, 1), C({1, eps, 0}, {0, 1, 0}, 1)},
        {C({0, 0, 0}, {0, 0, 1}, 1), C({2 + eps, 0, 0}, {0, 0, 1}, 1)},
    };
    for (const auto& p : pairs) {
      const auto r = expect_matches_brute_force(p[0], p[1], 1e-9);
      const auto s = circle3_circle3_distance_exact(p[1], p[0]);
      EXPECT_LE(r.lower, s.upper);
      EXPECT_LE(s.lower, r.upper);
    }
  }
}

}  // namespace
}  // namespace revdist
