// Tests of exact/solid_distance_exact: closed-form distances between solids
// (expected value inside the proven [lower, upper], tolerance 0), the width
// target 1e-9 x scale, swap symmetry, overlap and containment, and witnesses.
#include "exact/solid_distance_exact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case_io.h"

namespace revdist {
namespace {

Piece line(Vec2 p0, Vec2 p1) {
  Piece p;
  p.kind = PieceKind::line;
  p.degree = 1;
  p.points = {p0, p1};
  return p;
}
Piece arc(Vec2 p0, Vec2 pm, Vec2 p1) {
  Piece p;
  p.kind = PieceKind::arc;
  p.degree = 2;
  p.points = {p0, pm, p1};
  return p;
}

Profile sphere(double r) { return Profile{{arc({0, -r}, {r, 0}, {0, r})}, false}; }
Profile cylinder(double R, double h) {
  return Profile{{line({0, 0}, {R, 0}), line({R, 0}, {R, h}), line({R, h}, {0, h})}, false};
}
Profile torus(double R, double r) {
  return Profile{{arc({R - r, 0}, {R, -r}, {R + r, 0}), arc({R + r, 0}, {R, r}, {R - r, 0})}, true};
}
// A cup: outer radius 2, height 3, cavity of radius 1.5 above a floor at 0.5.
Profile cup() {
  return Profile{{line({0, 0}, {2, 0}), line({2, 0}, {2, 3}), line({2, 3}, {1.5, 3}), line({1.5, 3}, {1.5, 0.5}),
                  line({1.5, 0.5}, {0, 0.5})},
                 false};
}
// A cubic Bezier "egg": a free-form piece, so the 3-D (u, psi, v) boxes are exercised.
Profile egg() {
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = 3;
  p.points = {{0, 0}, {1.2, 0}, {0.8, 2}, {0, 2}};
  return Profile{{p}, false};
}

Pose pose(Vec3 t, std::array<double, 4> q = {1, 0, 0, 0}) {
  Pose p;
  p.q = q;
  p.translation = t;
  return p;
}

ExactSolidResult check(const Profile& a, const Pose& pa, const Profile& b, const Pose& pb, double expected,
                       const char* what, double rel = 1e-9) {
  SCOPED_TRACE(what);
  ExactSolidResult first;
  for (int swap = 0; swap < 2; ++swap) {
    SCOPED_TRACE(swap ? "swapped" : "as given");
    ExactSolidOptions opt;
    opt.relative_width = rel;
    const ExactSolidResult r = swap ? solid_distance_exact(b, pb, a, pa, opt) : solid_distance_exact(a, pa, b, pb, opt);
    std::printf("%-34s %s lower %.17g upper %.17g width %.3g boxes %ld time %.1f ms %s\n", what,
                swap ? "swap" : "    ", r.lower, r.upper, r.upper - r.lower, r.boxes, r.time_ms, r.reason.c_str());
    EXPECT_TRUE(r.certified) << r.reason;
    EXPECT_TRUE(r.width_reached) << r.reason;
    EXPECT_LE(r.lower, expected);
    EXPECT_GE(r.upper, expected);
    EXPECT_LE(r.upper - r.lower, rel * r.scale);
    if (expected > 0) {
      EXPECT_FALSE(r.overlap);
      // Witnesses: the pair realises the upper bound (up to double rounding of the points).
      const Vec3 pw_a = swap ? r.point_b : r.point_a, pw_b = swap ? r.point_a : r.point_b;
      EXPECT_NEAR((pw_a - pw_b).norm(), r.upper, 1e-12 * r.scale);
    }
    if (!swap) first = r;
  }
  return first;
}

// A query past its CPU budget (or asked to stop) ends with the bracket proven
// so far, certified, the reason saying which. One degree-8 Bezier against
// itself ran past 60 s within the box budget (second hostile-input review).
TEST(SolidDistanceExact, CpuBudgetAndStopEndTheSearchWithAProvenBracket) {
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = 8;
  for (int i = 0; i <= 8; ++i) {
    const double t = M_PI * (i / 8.0 - 0.5);
    p.points.emplace_back(1.2 * std::cos(t) * (i == 0 || i == 8 ? 0.0 : 1.0), std::sin(t));
  }
  const Profile s{{p}, false};
  ExactSolidOptions o;
  o.max_cpu_s = 0.01;  // the whole query takes ~0.25 s since its boxes are tight (2026-11-29)
  const ExactSolidResult r = solid_distance_exact(s, pose({0, 0, 0}), s, pose({2.5, 0, 0}, {0.9, 0.1, 0.3, 0.2}), o);
  EXPECT_TRUE(r.certified);
  EXPECT_LT(r.time_ms, 3000.0);
  EXPECT_LE(r.lower, r.upper);
  EXPECT_TRUE(std::isfinite(r.upper));
  EXPECT_FALSE(r.width_reached);
  EXPECT_NE(r.reason.find("CPU time budget"), std::string::npos) << r.reason;
  ExactSolidOptions stop;
  int asked = 0;
  stop.stop = [&] { return ++asked > 2; };
  const ExactSolidResult q = solid_distance_exact(s, pose({0, 0, 0}), s, pose({2.5, 0, 0}, {0.9, 0.1, 0.3, 0.2}), stop);
  EXPECT_TRUE(q.certified);
  if (!q.width_reached) {
    EXPECT_NE(q.reason.find("stop request"), std::string::npos) << q.reason;
  }
  EXPECT_LE(q.lower, r.upper);
  EXPECT_LE(r.lower, q.upper);
}

// A cylinder whose side is a line written as a Bezier of the given degree
// (degree-elevated: evenly spaced control points), height 2.2, radius 0.9
// (not dyadic: the splits round).
Profile bezier_side_cylinder(int degree) {
  Piece side;
  side.kind = PieceKind::bezier;
  side.degree = degree;
  for (int i = 0; i <= degree; ++i) side.points.emplace_back(0.9, 2.2 * i / degree);
  side.points.back() = {0.9, 2.2};
  return Profile{{line({0, 0}, {0.9, 0}), side, line({0.9, 2.2}, {0, 2.2})}, false};
}

// Two free-form sides (3-D boxes) of degree 8, axes crossed at right angles:
// the distance is the axes' distance less both radii, x - 1.8. The box bounds
// take the Bezier's range from its coefficients restricted to the box (an
// interval parameter in de Casteljau's recurrence widened the enclosure ~2x
// per degree: one degree-8 element stayed at [0, 0.503] after 300000 boxes),
// and doubles carry every box whose spread is far above their rounding (near
// contact every box went to MPFI: a gap of 1e-3 between two Bezier solids
// ended on the CPU budget after 280000 boxes, 100 us each).
//
// Degree 32 (the reader's limit) also: every array held 16 coefficients, so a
// Bezier of degree 16 to 32 left every box unbounded (no finite bracket), and
// de Casteljau written b_j + t (b_j+1 - b_j) doubled the coefficients' widths
// per degree (2^32 x rounding after one split).
TEST(SolidDistanceExact, HighDegreeBezierSidesConverge) {
  for (int degree : {8, 32}) {
    for (double x : {2.3, 1.801}) {
      SCOPED_TRACE(degree);
      SCOPED_TRACE(x);
      const Profile c = bezier_side_cylinder(degree);
      // Rotated a quarter turn about x (the exact rotation of q = (1, 1, 0, 0) / |q|):
      // B's axis runs from (x, 1.1, 1.1) to (x, -1.1, 1.1), A's from (0, 0, 0) to (0, 0, 2.2).
      const Pose pb = pose({x, 1.1, 1.1}, {1, 1, 0, 0});
      ExactSolidOptions o;
      o.max_boxes = 100000;
      o.max_cpu_s = 0;  // the box budget alone decides, on any machine
      const ExactSolidResult r = solid_distance_exact(c, pose({0, 0, 0}), c, pb, o);
      std::printf("crossed degree-%d cylinders at %g: [%.17g, %.17g] boxes %ld (mpfi %ld) %.1f ms\n", degree, x, r.lower,
                  r.upper, r.boxes, r.mpfi_boxes, r.time_ms);
      ASSERT_TRUE(r.certified) << r.reason;
      EXPECT_TRUE(r.width_reached) << r.reason;
      EXPECT_LE(r.lower, x - 1.8);
      EXPECT_GE(r.upper, x - 1.8);
      EXPECT_LE(r.boxes, 2000);  // degree 8 before both: 20000-28000
      EXPECT_LE(r.mpfi_boxes, r.boxes / 2);
    }
  }
}

// Two solids of one degree-32 Bezier whose control points zigzag (r = 0.7,
// 1.3, 0.7, ...): before, every box was unbounded (16 coefficients at most)
// and then, at the centres, de Casteljau's rounding doubled per degree, so the
// bracket stopped at a width of 2e-6. The fast engine's bracket (eps 1e-5, tol
// 1e-6: [0.965530491, 0.965531079]) must meet it.
TEST(SolidDistanceExact, ZigzagDegree32SolidsCertify) {
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = 32;
  p.points.emplace_back(0.0, 0.0);
  for (int i = 1; i < 32; ++i) p.points.emplace_back(i % 2 ? 0.7 : 1.3, 2.0 * i / 32);
  p.points.emplace_back(0.0, 2.0);
  const Profile s{{p}, false};
  ExactSolidOptions o;
  o.max_boxes = 20000;
  o.max_cpu_s = 0;
  const ExactSolidResult r = solid_distance_exact(s, pose({0, 0, 0}), s, pose({2.6, 0.1, 0.2}, {0.9, 0.1, 0.3, 0.2}), o);
  std::printf("zigzag degree 32: [%.17g, %.17g] boxes %ld %.1f ms\n", r.lower, r.upper, r.boxes, r.time_ms);
  ASSERT_TRUE(r.certified) << r.reason;
  EXPECT_TRUE(r.width_reached) << r.reason;
  EXPECT_LE(r.lower, 0.965531079);
  EXPECT_GE(r.upper, 0.965530491);
}

// Two spheres drawn as rational quadratic quarter circles (weight the double
// nearest sqrt(2)/2, so circles to ~1e-16), searched by boxes alone (no tube
// pairs): two free-form elements, whose bound takes the larger of g's form and
// the chord of E's part less its control points' distance from it. An arc
// bulges towards the other sphere past its chord: a chord bound that forgot
// that distance would rise above the true gap.
TEST(SolidDistanceExact, RationalBezierSpheresByBoxes) {
  const double w = 0.7071067811865476;
  auto sphere_of_quarters = [&](double r) {
    Piece lo, hi;
    lo.kind = hi.kind = PieceKind::bezier;
    lo.degree = hi.degree = 2;
    lo.points = {{0, -r}, {r, -r}, {r, 0}};
    hi.points = {{r, 0}, {r, r}, {0, r}};
    lo.weights = hi.weights = {1, w, 1};
    return Profile{{lo, hi}, false};
  };
  // (1, 0.5) as TwoSpheres; a small sphere's patch against a wide part of a
  // large one's arc is where a wrong chord bound shows first.
  for (const auto [ra, rb] : {std::pair{1.0, 0.5}, std::pair{0.02, 1.0}})
    for (int swap = 0; swap < 2; ++swap) {
      SCOPED_TRACE(ra);
      SCOPED_TRACE(swap);
      const double e = std::sqrt(5.25) - ra - rb;
      ExactSolidOptions o;
      o.use_structure = false;
      const Profile a = sphere_of_quarters(ra), b = sphere_of_quarters(rb);
      const Pose pa = pose({0, 0, 0}), pb = pose({2, 1, 0.5}, {0.9, 0.1, 0.3, 0.2});
      const ExactSolidResult r = swap ? solid_distance_exact(b, pb, a, pa, o) : solid_distance_exact(a, pa, b, pb, o);
      std::printf("rational Bezier spheres %g, %g %s: [%.17g, %.17g] boxes %ld %.1f ms\n", ra, rb, swap ? "swap" : "    ",
                  r.lower, r.upper, r.boxes, r.time_ms);
      ASSERT_TRUE(r.certified) << r.reason;
      EXPECT_TRUE(r.width_reached) << r.reason;
      EXPECT_LE(r.lower, e + 1e-14);  // the weight's rounding moves the surfaces by ~1e-16
      EXPECT_GE(r.upper, e - 1e-14);
      // Every bracket on the way is a proof too, the coarse ones most of all
      // (an error in a bound of wide boxes shrinks away with them).
      for (long budget : {4L, 8L, 16L, 32L, 64L, 128L, 256L, 512L}) {
        o.max_boxes = budget;
        const ExactSolidResult q = swap ? solid_distance_exact(b, pb, a, pa, o) : solid_distance_exact(a, pa, b, pb, o);
        EXPECT_LE(q.lower, e + 1e-14) << budget << " boxes";
        EXPECT_GE(q.upper, e - 1e-14) << budget << " boxes";
      }
    }
}

// Two unit spheres of 40 arcs each (points on the unit circle: the arcs'
// computed centres differ in their last bits). The tube bounds certified one
// circle pair per pair of distinct keys (1600) and tried every certified pair
// on every job: two 100-arc spheres ran 5 minutes. Near-equal circles now share
// one certificate, moved by their difference.
TEST(SolidDistanceExact, ManyArcSpheresShareTheirCircles) {
  auto sphere_of_arcs = [](int n) {
    Profile p;
    auto at = [&](int i2) {  // the point at angle pi * i2 / (2 n), from the south pole
      const double a = M_PI * i2 / (2.0 * n);
      return Vec2(i2 == 0 || i2 == 2 * n ? 0.0 : std::sin(a), -std::cos(a));
    };
    for (int i = 0; i < n; ++i) p.pieces.push_back(arc(at(2 * i), at(2 * i + 1), at(2 * i + 2)));
    return p;
  };
  const Profile s = sphere_of_arcs(40);
  for (double x : {2.5, 2.001}) {
    SCOPED_TRACE(x);
    const Pose pb = pose({x, 0.1, 0.05}, {0.9, 0.1, 0.3, 0.2});
    const double e = std::sqrt(x * x + 0.0125) - 2.0;
    ExactSolidOptions o;
    o.max_cpu_s = 0;
    const ExactSolidResult r = solid_distance_exact(s, pose({0, 0, 0}), s, pb, o);
    std::printf("40-arc spheres at %g: [%.17g, %.17g] boxes %ld, %d circle pairs certified, %.1f ms\n", x, r.lower,
                r.upper, r.boxes, r.circle_pairs, r.time_ms);
    ASSERT_TRUE(r.certified) << r.reason;
    EXPECT_TRUE(r.width_reached) << r.reason;
    EXPECT_LE(r.lower, e + 1e-14);  // the arcs' points are on the unit circle to ~1e-16
    EXPECT_GE(r.upper, e - 1e-14);
    EXPECT_LE(r.circle_pairs, 4);
  }
  // A stop request (or the CPU budget) also ends the tube pass, which had no
  // check: the jobs it did not reach still get their boxes, so the bracket
  // holds, and the search does not start.
  ExactSolidOptions o;
  o.stop = [] { return true; };
  const ExactSolidResult r = solid_distance_exact(s, pose({0, 0, 0}), s, pose({2.5, 0.1, 0.05}, {0.9, 0.1, 0.3, 0.2}), o);
  const double e = std::sqrt(2.5 * 2.5 + 0.0125) - 2.0;
  std::printf("stopped at once: [%.17g, %.17g], %d of %d pairs settled, %ld boxes\n", r.lower, r.upper,
              r.closed_form_pairs, r.element_pairs, r.boxes);
  ASSERT_TRUE(r.certified);
  EXPECT_NE(r.reason.find("stop request"), std::string::npos) << r.reason;
  EXPECT_LE(r.lower, e + 1e-14);
  EXPECT_GE(r.upper, e - 1e-14);
  EXPECT_TRUE(std::isfinite(r.upper));
  EXPECT_LE(r.closed_form_pairs, 16);  // the tube pass stopped within its first 16 jobs
  EXPECT_LE(r.boxes, 4L * r.element_pairs);  // initial boxes only
}

TEST(SolidDistanceExact, TwoSpheres) {
  const double e = std::sqrt(5.25) - 1.5;  // |c| - r1 - r2
  check(sphere(1), pose({0, 0, 0}), sphere(0.5), pose({2, 1, 0.5}, {0.9, 0.1, 0.3, 0.2}), e, "two spheres");
}

TEST(SolidDistanceExact, TwoSpheresCoaxial) {
  check(sphere(1), pose({0, 0, 0}), sphere(0.5), pose({0, 0, 2.25}), 0.75, "two spheres coaxial");
}

TEST(SolidDistanceExact, SphereBesideCylinder) {
  check(cylinder(1, 2), pose({0, 0, 0}), sphere(0.5), pose({3, 0, 1}, {0.8, -0.2, 0.1, 0.4}), 1.5,
        "sphere beside cylinder");
}

TEST(SolidDistanceExact, CoaxialCylindersStacked) {
  check(cylinder(1, 2), pose({0, 0, 0}), cylinder(0.7, 1), pose({0, 0, 2.25}), 0.25, "coaxial cylinders stacked");
}

TEST(SolidDistanceExact, ParallelAxisCylinders) {
  const double e = std::sqrt(4.25) - 1.5;  // axis distance - radii; z ranges [0,2] and [1,3] overlap
  check(cylinder(1, 2), pose({0, 0, 0}), cylinder(0.5, 2), pose({2, 0.5, 1}), e, "parallel-axis cylinders");
}

// Squared distance between the core circles of two linked rings: A = (cos a, sin a, 0)
// and B = (cx + cos b, 0, cz + sin b), minimised by a grid and Newton's method in
// long double (an independent reference: no intervals, no meridian reduction).
double linked_core_distance(long double cx, long double cz) {
  auto grad_hess = [&](long double a, long double b, long double g[2], long double H[3]) {
    const long double X = std::cos(a) - cx - std::cos(b), Z = -cz - std::sin(b);
    g[0] = -2 * X * std::sin(a) + std::sin(2 * a);
    g[1] = 2 * X * std::sin(b) - 2 * Z * std::cos(b);
    H[0] = 2 * std::sin(a) * std::sin(a) - 2 * X * std::cos(a) + 2 * std::cos(2 * a);
    H[1] = -2 * std::sin(a) * std::sin(b);
    H[2] = 2 + 2 * X * std::cos(b) + 2 * Z * std::sin(b);
  };
  auto f = [&](long double a, long double b) {
    const long double X = std::cos(a) - cx - std::cos(b), Y = std::sin(a), Z = -cz - std::sin(b);
    return X * X + Y * Y + Z * Z;
  };
  long double best = 1e30L, ba = 0, bb = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const long double a = 2 * M_PI * i / n, b = 2 * M_PI * j / n;
      if (f(a, b) < best) best = f(a, b), ba = a, bb = b;
    }
  for (int it = 0; it < 40; ++it) {
    long double g[2], H[3];
    grad_hess(ba, bb, g, H);
    const long double det = H[0] * H[2] - H[1] * H[1];
    ba -= (H[2] * g[0] - H[1] * g[1]) / det;
    bb -= (H[0] * g[1] - H[1] * g[0]) / det;
  }
  return static_cast<double>(std::sqrt(f(ba, bb)));
}

TEST(SolidDistanceExact, LinkedTori) {
  // Ring B in the xz-plane (rotation about x by 90 degrees), centre (0.8, 0, 0.1),
  // linked through ring A: solid tori of tube r are (core distance - 2r) apart.
  const double R = 1.0, r = 0.25, h = std::sqrt(0.5);
  const double e = linked_core_distance(0.8L, 0.1L) - 2 * r;
  check(torus(R, r), pose({0, 0, 0}), torus(R, r), pose({0.8, 0, 0.1}, {h, h, 0, 0}), e, "linked tori");
}

TEST(SolidDistanceExact, LinkedToriPerpendicularContinuum) {
  // Congruent rings in perpendicular planes, each through the other's centre:
  // |P_A - P_B|^2 = R^2 (3 - 2 cos a + 2 cos b (1 - cos a)) >= R^2, with equality at
  // cos b = -1 for EVERY a: B's point at A's centre is R from all of A's core. The
  // tori are R - 2r apart along a whole circle of closest pairs. The search alone
  // cannot narrow it (every box on the circle stays live); the tube path settles it.
  const double R = 1.0, r = 0.25, h = std::sqrt(0.5);
  const ExactSolidResult x = check(torus(R, r), pose({0, 0, 0}), torus(R, r), pose({R, 0, 0}, {h, h, 0, 0}),
                                   R - 2 * r, "linked tori (perpendicular continuum)");
  EXPECT_GT(x.closed_form_pairs, 0);
  EXPECT_EQ(x.boxes, 0);
}

TEST(SolidDistanceExact, BallInCupCavity) {
  // Coaxial: the nearest wall is the cavity side, 1.5 - 1 = 0.5 (floor 0.7, rim 0.7).
  check(cup(), pose({0, 0, 0}), sphere(1), pose({0, 0, 2.2}), 0.5, "ball in cup (coaxial)");
  // Off axis by 0.2: cavity wall 1.5 - 0.2 - 1 = 0.3.
  check(cup(), pose({0, 0, 0}), sphere(1), pose({0.2, 0, 2.2}, {0.7, 0.1, -0.3, 0.2}), 0.3, "ball in cup (off axis)");
}

TEST(SolidDistanceExact, FreeFormAgainstSphere) {
  // Egg's tip at (0, 0, 2) on its axis; a sphere straight above: 0.5 gap (coaxial).
  check(egg(), pose({0, 0, 0}), sphere(0.5), pose({0, 0, 3}), 0.5, "egg tip to sphere (coaxial)");
}

TEST(SolidDistanceExact, FreeFormAgainstFreeForm) {
  // Two eggs side by side, one rotated a quarter turn about its own axis (same
  // solid): both cubic pieces, so the boxes are 3-D (u, s, v). Closed form: the
  // widest circle of the egg, radius max r(u), found by Newton on r'(u) = 0 below.
  // r(u) = 3.6 u (1-u)^2 + 2.4 u^2 (1-u) = 3.6u - 4.8u^2 + 1.2u^3; r' = 3.6 - 9.6u + 3.6u^2.
  const long double u = (9.6L - std::sqrt(9.6L * 9.6L - 4 * 3.6L * 3.6L)) / (2 * 3.6L);
  const double rmax = static_cast<double>(3.6L * u - 4.8L * u * u + 1.2L * u * u * u);
  const double h = std::sqrt(0.5);
  check(egg(), pose({0, 0, 0}), egg(), pose({3, 0, 0}, {h, 0, 0, h}), 3 - 2 * rmax, "egg beside egg");
}

TEST(SolidDistanceExact, Overlap) {
  for (int swap = 0; swap < 2; ++swap) {
    const ExactSolidResult r = swap ? solid_distance_exact(sphere(1), pose({1.5, 0, 0}), sphere(1), pose({0, 0, 0}))
                                    : solid_distance_exact(sphere(1), pose({0, 0, 0}), sphere(1), pose({1.5, 0, 0}));
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(r.overlap);
    EXPECT_EQ(r.lower, 0.0);
    EXPECT_EQ(r.upper, 0.0);
  }
}

TEST(SolidDistanceExact, Containment) {
  for (int swap = 0; swap < 2; ++swap) {
    const Profile big = sphere(1), small = sphere(0.3);
    const Pose pb = pose({0, 0, 0}), ps = pose({0.2, -0.1, 0.3}, {0.9, 0.1, 0.3, 0.2});
    const ExactSolidResult r = swap ? solid_distance_exact(small, ps, big, pb) : solid_distance_exact(big, pb, small, ps);
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(r.overlap) << r.reason;
    EXPECT_EQ(r.upper, 0.0);
  }
  // A ball in the cup's cavity is not contained in the cup: positive distance (above).
}

TEST(SolidDistanceExact, TouchingIsZeroWithin) {
  // Spheres exactly touching: distance 0; the interval must contain 0 and be narrow.
  const ExactSolidResult r = solid_distance_exact(sphere(1), pose({0, 0, 0}), sphere(1), pose({2, 0, 0}));
  EXPECT_TRUE(r.certified);
  EXPECT_EQ(r.lower, 0.0);
  EXPECT_LE(r.upper, 1e-9 * r.scale) << r.reason;
}


// --- Structural paths (tube pairs), the double filter, progress, and the data ---

// The seed of a random test: REVDIST_SEED overrides the fallback; printed for replay.
std::uint64_t seed_of(std::uint64_t fallback, const char* what) {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t seed = s ? std::strtoull(s, nullptr, 10) : fallback;
  std::printf("[ seed     ] %s: REVDIST_SEED=%llu\n", what, static_cast<unsigned long long>(seed));
  return seed;
}

// Two proven brackets of one distance must meet.
void expect_meet(const ExactSolidResult& x, const ExactSolidResult& y, const char* what) {
  EXPECT_LE(x.lower, y.upper) << what;
  EXPECT_LE(y.lower, x.upper) << what;
}

TEST(SolidDistanceExact, TubePairsAgreeWithSearchOnRandomTori) {
  // Closed form (circle distance minus tube radii) against the branch and bound
  // alone on the same exact curves, random poses and tube radii.
  std::mt19937_64 rng(seed_of(7, "TubePairsAgreeWithSearchOnRandomTori"));
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int k = 0; k < 4; ++k) {
    const double Ra = 1.0 + 0.5 * U(rng), ra = 0.2 + 0.1 * U(rng);
    const double Rb = 1.0 + 0.5 * U(rng), rb = 0.2 + 0.1 * U(rng);
    const Pose pa = pose({0, 0, 0}, {1 + 0.3 * U(rng), U(rng), U(rng), U(rng)});
    const Pose pb = pose({2.5 + U(rng), U(rng), U(rng)}, {U(rng), U(rng), U(rng), 1.5});
    ExactSolidOptions tube;
    const ExactSolidResult x = solid_distance_exact(torus(Ra, ra), pa, torus(Rb, rb), pb, tube);
    ExactSolidOptions search;
    search.use_structure = false;
    search.relative_width = 1e-6;  // the search alone is slower; its bracket need only meet the other
    const ExactSolidResult y = solid_distance_exact(torus(Ra, ra), pa, torus(Rb, rb), pb, search);
    std::printf("tori %d: tube [%.17g, %.17g] (%d closed form, %ld boxes, %.1f ms); search [%.17g, %.17g] %.1f ms\n",
                k, x.lower, x.upper, x.closed_form_pairs, x.boxes, x.time_ms, y.lower, y.upper, y.time_ms);
    ASSERT_TRUE(x.certified && y.certified);
    EXPECT_TRUE(x.width_reached) << x.reason;
    EXPECT_GT(x.closed_form_pairs, 0);
    expect_meet(x, y, "tube vs search");
    EXPECT_NEAR((x.point_a - x.point_b).norm(), x.upper, 1e-12 * x.scale);  // witnesses realise the upper end
  }
}

// A ring of four rational quadratic quarter circles whose middle weight is the
// double nearest sqrt(2)/2: not exactly circles, so the tube path must prove an
// annulus around each (Bernstein bounds) rather than assume one.
Profile rounded_weight_ring(double R, double r) {
  const double w = 0.7071067811865476;
  auto quarter = [&](Vec2 p0, Vec2 p1, Vec2 p2) {
    Piece p;
    p.kind = PieceKind::bezier;
    p.degree = 2;
    p.points = {p0, p1, p2};
    p.weights = {1, w, 1};
    return p;
  };
  return Profile{{quarter({R + r, 0}, {R + r, r}, {R, r}), quarter({R, r}, {R - r, r}, {R - r, 0}),
                  quarter({R - r, 0}, {R - r, -r}, {R, -r}), quarter({R, -r}, {R + r, -r}, {R + r, 0})},
                 true};
}

TEST(SolidDistanceExact, RoundedWeightRingsLinkedContinuum) {
  const double R = 1.0, r = 0.25, h = std::sqrt(0.5);
  const ExactSolidResult x = check(rounded_weight_ring(R, r), pose({0, 0, 0}), rounded_weight_ring(R, r),
                                   pose({R, 0, 0}, {h, h, 0, 0}), R - 2 * r, "rounded-weight rings (continuum)");
  EXPECT_GT(x.closed_form_pairs, 0);
}

TEST(SolidDistanceExact, SphereAroundPointAndCoaxialTori) {
  // A sphere's arcs are tubes around a point (a circle of radius 0): closed form.
  const ExactSolidResult s = check(sphere(0.5), pose({0.1, 0.2, 0.3}), sphere(2), pose({4, 0.2, 0.3}, {0.8, 0.1, 0.2, 0.3}),
                                   1.4, "sphere vs sphere (points as circles)");
  EXPECT_GT(s.closed_form_pairs, 0);
  // Coaxial tori one above the other: equidistant along the whole circle.
  const ExactSolidResult t = check(torus(1, 0.25), pose({0, 0, 0}), torus(1, 0.25), pose({0, 0, 1}), 0.5,
                                   "coaxial stacked tori (continuum)");
  EXPECT_GT(t.closed_form_pairs, 0);
}

TEST(SolidDistanceExact, DoubleBoundsAgreeWithMpfiBounds) {
  // The double filter is a second, looser proof of the same boxes: brackets meet,
  // and both reach the width target. Free-form (3-D boxes) and lines (2-D).
  const Pose pe = pose({1.6, 0.2, 0.4}, {0.9, 0.1, 0.3, 0.2});
  for (int k = 0; k < 2; ++k) {
    const Profile other = k == 0 ? egg() : cylinder(0.5, 1.0);
    ExactSolidOptions on, off;
    // MPFI-only runs ~10x slower; a narrower target would prove no more here.
    on.relative_width = off.relative_width = k == 0 ? 1e-5 : 1e-7;
    off.double_bounds = false;
    const ExactSolidResult x = solid_distance_exact(egg(), pose({0, 0, 0}), other, pe, on);
    const ExactSolidResult y = solid_distance_exact(egg(), pose({0, 0, 0}), other, pe, off);
    std::printf("doubles [%.17g, %.17g] %.1f ms; mpfi [%.17g, %.17g] %.1f ms (%ld mpfi boxes)\n", x.lower, x.upper,
                x.time_ms, y.lower, y.upper, y.time_ms, y.mpfi_boxes);
    ASSERT_TRUE(x.certified && y.certified);
    EXPECT_TRUE(x.width_reached && y.width_reached);
    EXPECT_EQ(y.mpfi_boxes, y.boxes);
    expect_meet(x, y, "doubles vs mpfi");
  }
}

TEST(SolidDistanceExact, ProgressReportsNestedBrackets) {
  std::vector<ExactProgress> seen;
  ExactSolidOptions o;
  o.progress_interval_s = 0.0;  // every check: at least one report on any query that searches
  o.use_structure = false;
  o.progress = [&](const ExactProgress& p) { seen.push_back(p); };
  const ExactSolidResult r = solid_distance_exact(egg(), pose({0, 0, 0}), egg(), pose({1.5, 0.3, 0.2}, {0.9, 0.3, 0.1, 0}), o);
  ASSERT_TRUE(r.certified);
  ASSERT_FALSE(seen.empty()) << r.boxes << " boxes";
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_LE(seen[i].lower, r.upper);
    EXPECT_GE(seen[i].upper, r.lower);
    EXPECT_LE(seen[i].boxes, r.boxes);
    if (i > 0) {
      EXPECT_GE(seen[i].boxes, seen[i - 1].boxes);
    }
  }
}

TEST(SolidDistanceExact, ConeAgainstRationalBellConverges) {
  // Regression: over a wide box the weight's interval reached 0, a cost became NaN
  // (0 x inf) and the box was taken for unsplittable, so the bracket stayed [0, 0.61].
  Piece bell;
  bell.kind = PieceKind::bezier;
  bell.degree = 4;
  bell.points = {{0, 0}, {1.2, 0.1}, {0.2, 0.7}, {0.9, 1.3}, {0, 1.6}};
  bell.weights = {1, 3, 0.5, 2, 1};
  const Profile cone{{line({0, 0}, {0.6, 0}), line({0.6, 0}, {0, 1.5})}, false};
  ExactSolidOptions o;
  const ExactSolidResult r =
      solid_distance_exact(cone, pose({1.9, 0.3, 0.2}, {0.9, 0.2, -0.3, 0.1}), Profile{{bell}, false}, pose({0, 0, 0}), o);
  std::printf("cone vs bell [%.17g, %.17g] %ld boxes %.1f ms\n", r.lower, r.upper, r.boxes, r.time_ms);
  ASSERT_TRUE(r.certified);
  EXPECT_TRUE(r.width_reached) << r.reason;
  EXPECT_GT(r.lower, 0.35);  // fast/ brackets it at 0.3506531173 (tol 1e-9)
  EXPECT_LT(r.upper, 0.351);
}

// A sanitized build (scripts/sanitize.sh) runs exact/ 5-6 times slower: a
// time budget scales by this (a regression case certified in 0.57 s in
// Release took 3.6 s of its 2 s under AddressSanitizer).
#ifdef REVDIST_SANITIZED
constexpr double kBudgetScale = 8.0;
#else
constexpr double kBudgetScale = 1.0;
#endif

// Every query of the bundled distance cases and regressions: certified, to the
// default width 1e-9 x scale, each within 2 s of CPU (the engine's target),
// or within the file's "exact_time_budget_ms" where it records that the
// engine misses its target there (a known slow case, kept in view); times
// kBudgetScale in a sanitized build.
TEST(SolidDistanceExact, BundledCasesCertifyQuickly) {
  for (const char* dir : {"cases/distance", "cases/regressions"}) {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(std::string(REVDIST_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) {
      const Case c = read_case(f);
      double budget_ms = 2000.0;
      {
        std::ifstream in(f);
        const nlohmann::json j = nlohmann::json::parse(in);
        if (j.contains("exact_time_budget_ms")) budget_ms = j.at("exact_time_budget_ms").get<double>();
      }
      for (const auto& [ia, ib] : c.queries) {
        const Instance& A = c.instances[ia];
        const Instance& B = c.instances[ib];
        const ExactSolidResult r = solid_distance_exact(profile_at(c.solids[A.solid], A.time), A.pose,
                                                        profile_at(c.solids[B.solid], B.time), B.pose);
        SCOPED_TRACE(f + " " + A.name + "-" + B.name);
        EXPECT_TRUE(r.certified) << r.reason;
        EXPECT_TRUE(r.width_reached) << r.reason;
        EXPECT_LE(r.upper - r.lower, 1e-9 * r.scale);
        EXPECT_LT(r.time_ms, kBudgetScale * budget_ms);
      }
    }
  }
}

}  // namespace
}  // namespace revdist
